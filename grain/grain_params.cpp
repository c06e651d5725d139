#include "grain/grain_params.h"

#include <fmt/format.h>

#include <cmath>

#include "util/json_reader.h"
#include "util/limits.h"

namespace nenrin {

namespace {

Rgb readRgb(JsonReader& r, const std::string& key, const Rgb& fallback, double lo) {
    Vec3 v = r.vec3(key, {fallback.r, fallback.g, fallback.b});
    for (int i = 0; i < 3; ++i)
        if (!(v[i] >= lo && v[i] <= 1))
            throw r.error(key,
                          fmt::format("expected colour components in [{}, 1], found {}", lo, v[i]));
    return {v.x, v.y, v.z};
}

nlohmann::json rgbJson(const Rgb& c) { return {c.r, c.g, c.b}; }

nlohmann::json endGrainJson(const ColourParams& c) {
    nlohmann::json j = {{"darkening", c.endGrainDarkening},
                        {"redness", c.endGrainRedness},
                        {"texture", c.endGrainTexture},
                        {"contrast", c.endGrainContrast}};
    if (c.endGrainTint.r >= 0) j["tint"] = rgbJson(c.endGrainTint);
    return j;
}

/// The measured displacement lattice (docs/grain-format.md, "warp").
void readWarp(JsonReader& r, WarpParams& w) {
    w.origin = r.requireVec3("origin");
    w.step = r.requireVec3("step");
    for (double s : {w.step.x, w.step.y, w.step.z})
        if (!(s >= kMinWarpStep))
            throw r.error("step", "expected lattice steps of at least 0.1 mm (metres)");
    const std::vector<double> size = r.numberList("size");
    if (size.size() != 3)
        throw r.error("size", "expected the node counts [nx, ny, nz], each 2 to 64");
    int n[3];
    for (int i = 0; i < 3; ++i) {
        if (!(size[size_t(i)] >= 2 && size[size_t(i)] <= 64 &&
              size[size_t(i)] == std::floor(size[size_t(i)])))
            throw r.error("size", "expected the node counts [nx, ny, nz], each 2 to 64");
        n[i] = int(size[size_t(i)]);
    }
    w.nx = n[0], w.ny = n[1], w.nz = n[2];
    w.displacement = r.requireVec3List("displacement");
    const size_t nodes = size_t(w.nx) * w.ny * w.nz;
    if (w.displacement.size() != nodes)
        throw r.error("displacement", fmt::format("expected {} vectors (nx ny nz), found {}", nodes,
                                                  w.displacement.size()));
    for (const Vec3& d : w.displacement)
        if (!(length(d) <= kMaxWarp))
            throw r.error("displacement", "expected displacements of at most 5 cm (metres)");
    r.finish();
}

/// The growth terms' parameters: the junction blend (eq. 5), direction (eq. 7), age (eq. 8),
/// taper (eq. 9), sway (section 4.5) and the rings' centimetre-scale wander.
void readGrowthTerms(JsonReader& root, GrainParams& g) {
    if (auto j = root.object("junction")) {
        g.junction.p = j->inRange("p", g.junction.p, 0.5, 64);
        g.junction.reach = j->inRange("reach", g.junction.reach, 1.5, 100);
        j->finish();
    }
    if (auto d = root.object("direction")) {
        Vec3 sun = d->vec3("sun_ray", g.direction.sunRay);
        if (length(sun) < 1e-12) throw d->error("sun_ray", "expected a non-zero vector");
        g.direction.sunRay = normalize(sun);
        g.direction.strength = d->inRange("strength", g.direction.strength, 0, 0.95);
        d->finish();
    }
    if (auto a = root.object("age")) {
        g.age.delta = a->inRange("delta", g.age.delta, 0.2, 5);
        a->finish();
    }
    if (auto t = root.object("taper")) {
        g.taper.nu = t->inRange("nu", g.taper.nu, 0, 10);
        g.taper.omega = t->inRange("omega", g.taper.omega, 1e-6, 1);
        t->finish();
    }
    if (auto s = root.object("sway")) {
        g.sway.amplitude = s->inRange("amplitude", g.sway.amplitude, 0, 1);
        g.sway.wavelength = s->atLeast("wavelength", g.sway.wavelength, kMinSwayWavelength,
                                       "m: sway bends rings over centimetres or more");
        g.sway.radialJitter = s->inRange("radial_jitter", g.sway.radialJitter, 0, 0.9);
        g.sway.seed = static_cast<uint64_t>(s->integer("seed", 1, 0, 1LL << 53));
        s->finish();
    }
    if (auto w = root.object("wander")) {
        g.wander.amplitude = w->inRange("amplitude", g.wander.amplitude, 0, 0.05);
        g.wander.wavelength = w->atLeast("wavelength", g.wander.wavelength, kMinWanderWavelength,
                                         "m: rings wander over millimetres or more");
        g.wander.along = w->atLeast("along", g.wander.along, kMinWanderWavelength,
                                    "m: rings wander over millimetres or more");
        g.wander.octaves = static_cast<int>(w->integer("octaves", g.wander.octaves, 1, 4));
        g.wander.seed = static_cast<uint64_t>(w->integer("seed", 1, 0, 1LL << 53));
        w->finish();
    }
    if (auto w = root.object("warp")) readWarp(*w, g.warp);
}

/// The stochastic ring-width model (docs/grain-format.md, "rings").
void readRingModel(JsonReader& r, RingModelParams& m) {
    m.enabled = r.choice("model", "stochastic", {"stochastic", "constant"}) == "stochastic";
    m.meanWidth = r.zeroOrAtLeast("mean_width", m.meanWidth, kMinRingWidth,
                                  "m: 1 um; 0 takes the radial speed");
    if (m.meanWidth > 0.1)
        throw r.error("mean_width",
                      fmt::format("expected at most 0.1 (m), found {:g}", m.meanWidth));
    m.juvenileFactor = r.inRange("juvenile_factor", m.juvenileFactor, 1, 10);
    m.juvenileYears = r.inRange("juvenile_years", m.juvenileYears, 0.5, 500);
    m.variation = r.inRange("variation", m.variation, 0, 2);
    m.autocorrelation = r.inRange("autocorrelation", m.autocorrelation, 0, 0.95);
    m.climateShare = r.inRange("climate_share", m.climateShare, 0, 1);
    m.years = static_cast<int>(r.integer("years", 0, 0, 5000));
    m.seed = static_cast<uint64_t>(r.integer("seed", 1, 0, 1LL << 53));
    m.climateSeed = static_cast<uint64_t>(r.integer("climate_seed", 1, 0, 1LL << 53));
    m.replaceRecorded = r.boolean("replace_recorded", false);
    r.finish();
}

/// Fibres, pores, rays and resin canals.
void readAnatomy(JsonReader& a, AnatomyParams& m) {
    m.enabled = a.boolean("enabled", true);
    m.seed = static_cast<uint64_t>(a.integer("seed", 1, 0, 1LL << 53));
    m.colourLine = a.boolean("colour_line", m.colourLine);
    if (auto f = a.object("fibres")) {
        m.fibreAmplitude = f->inRange("amplitude", m.fibreAmplitude, 0, 0.5);
        m.fibreWidth = f->inRange("width", m.fibreWidth, 1e-5, 0.01);
        m.fibreLength = f->inRange("length", m.fibreLength, 1e-4, 1);
        f->finish();
    }
    if (auto k = a.object("streaks")) {
        m.streakAmplitude = k->inRange("amplitude", m.streakAmplitude, 0, 0.5);
        m.streakWidth = k->inRange("width", m.streakWidth, 1e-4, 0.1);
        m.streakLength = k->inRange("length", m.streakLength, 1e-3, 1);
        k->finish();
    }
    m.ringTone = a.inRange("ring_tone", m.ringTone, 0, 0.5);
    if (auto k = a.object("speckle")) {
        m.speckleAmplitude = k->inRange("amplitude", m.speckleAmplitude, 0, 0.5);
        m.speckleSize = k->inRange("size", m.speckleSize, 1e-5, 0.01);
        m.speckleLength = k->inRange("length", m.speckleLength, 1e-5, 0.1);
        m.speckleRadial = k->inRange("radial", m.speckleRadial, 0, 0.01);
        if (m.speckleRadial > 0 && m.speckleRadial < 1e-5)
            throw k->error("radial", "expected 0 (as size) or at least 1e-05 (m)");
        k->finish();
    }
    if (auto v = a.object("pores")) {
        std::string kind = v->choice("kind", "none", {"none", "ring-porous", "diffuse-porous"});
        m.pores = kind == "ring-porous"      ? PoreKind::RingPorous
                  : kind == "diffuse-porous" ? PoreKind::DiffusePorous
                                             : PoreKind::None;
        m.poreDiameter = v->inRange("diameter", m.poreDiameter, 1e-5, 0.002);
        m.poreSpacing = v->inRange("spacing", m.poreSpacing, 2e-5, 0.01);
        m.poreLength = v->inRange("length", m.poreLength, 1e-4, 0.1);
        m.poreBand = v->inRange("band", m.poreBand, 0.01, 1);
        m.poreDarkening = v->inRange("darkening", m.poreDarkening, 0, 1);
        if (v->has("tint")) m.poreTint = readRgb(*v, "tint", m.poreTint, 0);
        m.poreDepth = v->inRange("depth", m.poreDepth, 0, 2);
        v->finish();
    }
    if (auto r = a.object("rays")) {
        m.raySpacing = r->inRange("spacing", m.raySpacing, 1e-4, 0.05);
        m.rayWidth = r->inRange("width", m.rayWidth, 0, 0.005);
        m.rayHeight = r->inRange("height", m.rayHeight, 1e-5, 0.1);
        m.rayContrast = r->inRange("contrast", m.rayContrast, -0.9, 1);
        r->finish();
    }
    if (auto r = a.object("resin_canals")) {
        m.resinSpacing = r->inRange("spacing", m.resinSpacing, 0, 0.05);
        m.resinDiameter = r->inRange("diameter", m.resinDiameter, 1e-5, 0.002);
        m.resinDarkening = r->inRange("darkening", m.resinDarkening, 0, 1);
        r->finish();
    }
    a.finish();
}

/// The early-to-late-wood profile measured from a photograph (nenrin grain strip).
void readLateWoodProfile(JsonReader& c, ColourParams& cp) {
    if (!c.has("late_wood_profile")) return;
    cp.lateWoodProfile = c.numberList("late_wood_profile");
    if (cp.lateWoodProfile.size() < 2 || cp.lateWoodProfile.size() > 1024)
        throw c.error("late_wood_profile", fmt::format("{} values: expected 2 to 1024 values of E "
                                                       "over one ring",
                                                       cp.lateWoodProfile.size()));
    for (size_t i = 0; i < cp.lateWoodProfile.size(); ++i)
        if (!(cp.lateWoodProfile[i] >= 0 && cp.lateWoodProfile[i] <= 1))
            throw c.error("late_wood_profile", fmt::format("value {} is {}: expected E in [0, 1]",
                                                           i, cp.lateWoodProfile[i]));
}

/// Knot colours: darkening, core, a dead knot's rim and checks, tints, the halo round them,
/// the rings' wobble.
void readKnotColours(JsonReader& k, ColourParams& cp) {
    cp.knotDarkening = k.inRange("darkening", cp.knotDarkening, 0, 1);
    cp.deadKnotDarkening = k.inRange("dead_darkening", cp.deadKnotDarkening, 0, 1);
    cp.knotCore = k.inRange("core", cp.knotCore, 0, 1);
    cp.knotRingDarkening = k.inRange("ring_darkening", cp.knotRingDarkening, 0, 0.9);
    cp.deadKnotRim = k.inRange("dead_rim", cp.deadKnotRim, 0, 1);
    cp.deadKnotRimWidth = k.inRange("dead_rim_width", cp.deadKnotRimWidth, 0, 0.05);
    cp.deadKnotChecks = k.inRange("dead_checks", cp.deadKnotChecks, 0, 1);
    cp.deadKnotCheckWidth = k.inRange("dead_check_width", cp.deadKnotCheckWidth, 0, 0.01);
    cp.knotTint = readRgb(k, "tint", cp.knotTint, 0);
    cp.deadKnotTint = readRgb(k, "dead_tint", cp.deadKnotTint, 0);
    cp.knotHaloTint = readRgb(k, "halo_tint", cp.knotHaloTint, 0);
    cp.knotHaloWidth = k.inRange("halo_width", cp.knotHaloWidth, 0, 0.1);
    cp.knotHaloAxial = k.inRange("halo_axial", cp.knotHaloAxial, 1, 20);
    cp.knotRingWobble = k.inRange("ring_wobble", cp.knotRingWobble, 0, 2);
    cp.knotRingWobbleScale = k.inRange("ring_wobble_scale", cp.knotRingWobbleScale, 0.0005, 0.05);
    k.finish();
}

/// The wood's colour: early and late wood, their profile, heartwood, micro-structure, knots
/// and the end grain.
void readColour(JsonReader& c, ColourParams& cp) {
    cp.earlyWood = readRgb(c, "early_wood", cp.earlyWood, 0);
    cp.lateWood = readRgb(c, "late_wood", cp.lateWood, 0);
    cp.lateWoodExponent = c.inRange("late_wood_exponent", cp.lateWoodExponent, 0.1, 100);
    cp.lateWoodShare = c.inRange("late_wood_share", cp.lateWoodShare, 0, 0.9);
    cp.lateWoodTransition = c.inRange("late_wood_transition", cp.lateWoodTransition, 0.005, 0.5);
    cp.earlyWoodRise = c.inRange("early_wood_rise", cp.earlyWoodRise, 0, 0.45);
    cp.lateWoodRamp = c.inRange("late_wood_ramp", cp.lateWoodRamp, 0, 0.5);
    readLateWoodProfile(c, cp);
    if (auto h = c.object("heartwood")) {
        cp.heartwood = h->boolean("enabled", cp.heartwood);
        cp.heartwoodStart = h->nonNegative("start", cp.heartwoodStart);
        cp.heartwoodEnd = h->nonNegative("end", cp.heartwoodEnd);
        if (cp.heartwoodEnd < cp.heartwoodStart)
            throw h->error("end", fmt::format("expected end >= start ({}), found {}",
                                              cp.heartwoodStart, cp.heartwoodEnd));
        cp.heartwoodOffset = readRgb(*h, "heartwood_offset", cp.heartwoodOffset, -1);
        cp.sapwoodOffset = readRgb(*h, "sapwood_offset", cp.sapwoodOffset, -1);
        h->finish();
    }
    if (auto m = c.object("micro")) {
        cp.microCellSize = m->atLeast("cell_size", cp.microCellSize, kMinCellSize, "m: 1 um");
        cp.microAmplitude = m->inRange("amplitude", cp.microAmplitude, 0, 1);
        cp.microSeed = static_cast<uint64_t>(m->integer("seed", 7, 0, 1LL << 53));
        m->finish();
    }
    if (auto k = c.object("knots")) readKnotColours(*k, cp);
    if (auto e = c.object("end_grain")) {
        cp.endGrainDarkening = e->inRange("darkening", cp.endGrainDarkening, 0, 0.9);
        cp.endGrainRedness = e->inRange("redness", cp.endGrainRedness, 0, 1);
        if (e->has("tint")) cp.endGrainTint = readRgb(*e, "tint", cp.endGrainTint, 0);
        cp.endGrainTexture = e->inRange("texture", cp.endGrainTexture, -0.9, 4);
        cp.endGrainContrast = e->inRange("contrast", cp.endGrainContrast, -0.9, 4);
        e->finish();
    }
    c.finish();
}

}  // namespace

GrainParams parseGrain(const nlohmann::json& json, const std::string& file) {
    GrainParams g;
    JsonReader root(json, file);
    root.string("description", "");
    root.choice("format", "nenrin-grain", {"nenrin-grain"});
    root.object("reference");  // what a preset was made from (colour measurements, sources):
                               // read by people and tests, not by nenrin
    g.radialSpeed = root.atLeast("radial_speed", g.radialSpeed, kMinRadialSpeed,
                                 "m/year: 0.01 mm a year, slower than any tree grows");
    g.fellingTime = root.nonNegative("felling_time", g.fellingTime);
    readGrowthTerms(root, g);
    if (auto r = root.object("rings")) readRingModel(*r, g.rings);
    if (auto a = root.object("anatomy")) readAnatomy(*a, g.anatomy);
    if (auto c = root.object("colour")) readColour(*c, g.colour);
    root.finish();
    return g;
}

GrainParams loadGrainFile(const std::string& path) { return parseGrain(parseJsonFile(path), path); }

namespace {

/// The "colour" object of a grain file.
nlohmann::json colourJson(const ColourParams& c) {
    nlohmann::json j = {
        {"early_wood", rgbJson(c.earlyWood)},
        {"late_wood", rgbJson(c.lateWood)},
        {"late_wood_exponent", c.lateWoodExponent},
        {"late_wood_share", c.lateWoodShare},
        {"late_wood_transition", c.lateWoodTransition},
        {"early_wood_rise", c.earlyWoodRise},
        {"late_wood_ramp", c.lateWoodRamp},
        {"late_wood_profile", c.lateWoodProfile},
        {"heartwood",
         {{"enabled", c.heartwood},
          {"start", c.heartwoodStart},
          {"end", c.heartwoodEnd},
          {"heartwood_offset", rgbJson(c.heartwoodOffset)},
          {"sapwood_offset", rgbJson(c.sapwoodOffset)}}},
        {"micro",
         {{"cell_size", c.microCellSize}, {"amplitude", c.microAmplitude}, {"seed", c.microSeed}}},
        {"knots",
         {{"darkening", c.knotDarkening},
          {"dead_darkening", c.deadKnotDarkening},
          {"core", c.knotCore},
          {"ring_darkening", c.knotRingDarkening},
          {"dead_rim", c.deadKnotRim},
          {"dead_rim_width", c.deadKnotRimWidth},
          {"dead_checks", c.deadKnotChecks},
          {"dead_check_width", c.deadKnotCheckWidth},
          {"tint", rgbJson(c.knotTint)},
          {"dead_tint", rgbJson(c.deadKnotTint)},
          {"halo_tint", rgbJson(c.knotHaloTint)},
          {"halo_width", c.knotHaloWidth},
          {"halo_axial", c.knotHaloAxial},
          {"ring_wobble", c.knotRingWobble},
          {"ring_wobble_scale", c.knotRingWobbleScale}}},
        {"end_grain", endGrainJson(c)}};
    // No measured profile: the key left out (a file cannot hold an empty one).
    if (c.lateWoodProfile.empty()) j.erase("late_wood_profile");
    return j;
}

/// The "anatomy" object of a grain file.
nlohmann::json anatomyJson(const AnatomyParams& m) {
    const char* kinds[] = {"none", "ring-porous", "diffuse-porous"};
    nlohmann::json j = {
        {"enabled", true},
        {"seed", m.seed},
        {"fibres",
         {{"amplitude", m.fibreAmplitude}, {"width", m.fibreWidth}, {"length", m.fibreLength}}},
        {"streaks",
         {{"amplitude", m.streakAmplitude}, {"width", m.streakWidth}, {"length", m.streakLength}}},
        {"ring_tone", m.ringTone},
        {"speckle",
         {{"amplitude", m.speckleAmplitude},
          {"size", m.speckleSize},
          {"radial", m.speckleRadial},
          {"length", m.speckleLength}}},
        {"pores",
         {{"kind", kinds[static_cast<int>(m.pores)]},
          {"diameter", m.poreDiameter},
          {"spacing", m.poreSpacing},
          {"length", m.poreLength},
          {"band", m.poreBand},
          {"darkening", m.poreDarkening},
          {"tint", rgbJson(m.poreTint)},
          {"depth", m.poreDepth}}},
        {"rays",
         {{"spacing", m.raySpacing},
          {"width", m.rayWidth},
          {"height", m.rayHeight},
          {"contrast", m.rayContrast}}},
        {"resin_canals",
         {{"spacing", m.resinSpacing},
          {"diameter", m.resinDiameter},
          {"darkening", m.resinDarkening}}}};
    // Written only when on: grain files written before it stay as they were.
    if (m.colourLine) j["colour_line"] = true;
    return j;
}

}  // namespace

nlohmann::json grainToJson(const GrainParams& g) {
    nlohmann::json j = {
        {"format", "nenrin-grain"},
        {"radial_speed", g.radialSpeed},
        {"felling_time", g.fellingTime},
        {"junction", {{"p", g.junction.p}, {"reach", g.junction.reach}}},
        {"direction",
         {{"sun_ray", {g.direction.sunRay.x, g.direction.sunRay.y, g.direction.sunRay.z}},
          {"strength", g.direction.strength}}},
        {"age", {{"delta", g.age.delta}}},
        {"taper", {{"nu", g.taper.nu}, {"omega", g.taper.omega}}},
        {"sway",
         {{"amplitude", g.sway.amplitude},
          {"wavelength", g.sway.wavelength},
          {"radial_jitter", g.sway.radialJitter},
          {"seed", g.sway.seed}}},
        {"wander",
         {{"amplitude", g.wander.amplitude},
          {"wavelength", g.wander.wavelength},
          {"along", g.wander.along},
          {"octaves", g.wander.octaves},
          {"seed", g.wander.seed}}},
        {"colour", colourJson(g.colour)},
    };
    if (g.rings.enabled) {
        const RingModelParams& m = g.rings;
        j["rings"] = {{"model", "stochastic"},
                      {"mean_width", m.meanWidth},
                      {"juvenile_factor", m.juvenileFactor},
                      {"juvenile_years", m.juvenileYears},
                      {"variation", m.variation},
                      {"autocorrelation", m.autocorrelation},
                      {"climate_share", m.climateShare},
                      {"years", m.years},
                      {"seed", m.seed},
                      {"climate_seed", m.climateSeed},
                      {"replace_recorded", m.replaceRecorded}};
    }
    if (g.anatomy.enabled) j["anatomy"] = anatomyJson(g.anatomy);
    if (g.warp.enabled()) {
        const WarpParams& w = g.warp;
        nlohmann::json d = nlohmann::json::array();
        for (const Vec3& v : w.displacement) d.push_back({v.x, v.y, v.z});
        j["warp"] = {{"origin", {w.origin.x, w.origin.y, w.origin.z}},
                     {"step", {w.step.x, w.step.y, w.step.z}},
                     {"size", {w.nx, w.ny, w.nz}},
                     {"displacement", d}};
    }
    return j;
}

}  // namespace nenrin
