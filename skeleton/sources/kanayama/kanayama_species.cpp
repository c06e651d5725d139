#include "skeleton/sources/kanayama/kanayama_species.h"

#include <cmath>
#include <limits>
#include <numbers>

#include "util/input_error.h"
#include "util/json_reader.h"

namespace nenrin {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kInf = std::numeric_limits<double>::infinity();

/// One real-valued species parameter: its JSON name, member, allowed range and whether the
/// file gives it in degrees. One table drives validation and JSON reading, so they never drift.
struct RealParameter {
    const char* name;
    double KanayamaSpecies::*member;
    double lo, hi;
    bool degrees;
};

struct IntParameter {
    const char* name;
    int KanayamaSpecies::*member;
    int lo, hi;
};

const RealParameter kRealParameters[] = {
    {"leafSize", &KanayamaSpecies::leafSize, 1e-3, 10, false},
    {"extinction", &KanayamaSpecies::extinction, 0, 1e4, false},
    {"deathLight", &KanayamaSpecies::deathLight, 0, 1, false},
    {"deathJitter", &KanayamaSpecies::deathJitter, 0, 1, false},
    {"alphaTerminal", &KanayamaSpecies::alphaTerminal, 0, 10, false},
    {"alphaLateral", &KanayamaSpecies::alphaLateral, 0, 10, false},
    {"beta", &KanayamaSpecies::beta, 0, 1, false},
    {"gamma", &KanayamaSpecies::gamma, 0, 1, false},
    {"production", &KanayamaSpecies::production, 1e-9, 1e9, false},
    {"maxVigour", &KanayamaSpecies::maxVigour, 1e-3, 100, false},
    {"seedlingVigour", &KanayamaSpecies::seedlingVigour, 0, 100, false},
    {"shortInternode", &KanayamaSpecies::shortInternode, 1e-4, 10, false},
    {"longInternodeMax", &KanayamaSpecies::longInternodeMax, 1e-4, 10, false},
    {"longShootVigour", &KanayamaSpecies::longShootVigour, 0, 0.999, false},
    {"phyllotaxis", &KanayamaSpecies::phyllotaxis, -360 * kDeg, 360 * kDeg, true},
    {"lateralAngle", &KanayamaSpecies::lateralAngle, 0, 180 * kDeg, true},
    {"sympodialBend", &KanayamaSpecies::sympodialBend, 0, 180 * kDeg, true},
    {"gravitropism", &KanayamaSpecies::gravitropism, -10, 10, false},
    {"phototropism", &KanayamaSpecies::phototropism, -10, 10, false},
    {"budBreak", &KanayamaSpecies::budBreak, 0, 1000, false},
    {"budBreakAgeStart", &KanayamaSpecies::budBreakAgeStart, 0, 1, false},
    {"budBreakAgeRate", &KanayamaSpecies::budBreakAgeRate, 0, 1, false},
    {"initialArea", &KanayamaSpecies::initialArea, 1e-12, 1, false},
    {"areaPerLeaf", &KanayamaSpecies::areaPerLeaf, 0, 1, false},
    {"seasonFraction", &KanayamaSpecies::seasonFraction, 1e-3, 1, false},
    {"directionJitter", &KanayamaSpecies::directionJitter, 0, 90 * kDeg, true},
    {"dormantBreakVigour", &KanayamaSpecies::dormantBreakVigour, 0, kInf, false},
    {"dormantDropRatio", &KanayamaSpecies::dormantDropRatio, 0, 1, false},
};

const IntParameter kIntParameters[] = {
    {"shortShootNodes", &KanayamaSpecies::shortShootNodes, 1, 1000},
    {"longShootMaxNodes", &KanayamaSpecies::longShootMaxNodes, 1, 1000},
    {"terminalLateralBuds", &KanayamaSpecies::terminalLateralBuds, 0, 16},
    {"lateralBudsPerNode", &KanayamaSpecies::lateralBudsPerNode, 0, 16},
    {"leavesPerNode", &KanayamaSpecies::leavesPerNode, 0, 1000},
    {"dormantBreakCount", &KanayamaSpecies::dormantBreakCount, 0, 1000},
    {"dormantLifetime", &KanayamaSpecies::dormantLifetime, 0, 1000},
};

std::string jsonName(const RealParameter& p) {
    return p.degrees ? std::string(p.name) + "Deg" : std::string(p.name);
}

std::string formatRange(double lo, double hi, bool degrees) {
    double s = degrees ? 1 / kDeg : 1;
    std::string h = std::isinf(hi) ? "inf" : std::to_string(hi * s);
    return "[" + std::to_string(lo * s) + ", " + h + "]";
}

// Parameters from the paper where it gives them (structure: monopodial cherry, sympodial
// zelkova and azalea; apical dominance strong in cherry, strong-then-weak in zelkova, weak in
// azalea); magnitudes tuned so 15-year heights land near Table 1 (docs/tree-kanayama.md).
KanayamaOptions cherry() {
    KanayamaOptions o;
    o.preset = "cherry";
    KanayamaSpecies& s = o.species;
    s.branching = KanayamaBranching::Monopodial;
    s.alphaTerminal = 1.0;
    s.alphaLateral = 0.35;
    s.beta = 0.7;
    s.gamma = 0.5;
    s.shortShootNodes = 3;
    s.longShootMaxNodes = 9;
    s.shortInternode = 0.004;
    s.longInternodeMax = 0.024;
    s.longShootVigour = 0.3;
    s.terminalLateralBuds = 1;
    s.lateralBudsPerNode = 1;
    s.phyllotaxis = 144 * kDeg;  // 2/5 spiral
    s.lateralAngle = 65 * kDeg;  // spreading crown
    s.gravitropism = 0.015;
    s.phototropism = 0.03;
    s.budBreak = 2.0;
    s.leafSize = 0.07;
    s.leavesPerNode = 1;
    return o;
}

KanayamaOptions zelkova() {
    KanayamaOptions o;
    o.preset = "zelkova";
    KanayamaSpecies& s = o.species;
    s.branching = KanayamaBranching::Sympodial;
    s.sympodialBend = 12 * kDeg;
    s.alphaTerminal = 1.0;
    s.alphaLateral = 0.3;
    s.beta = 0.7;
    s.gamma = 0.5;
    s.shortShootNodes = 3;
    s.longShootMaxNodes = 11;
    s.shortInternode = 0.004;
    s.longInternodeMax = 0.0245;
    s.longShootVigour = 0.3;
    s.terminalLateralBuds = 1;
    s.lateralBudsPerNode = 1;
    s.phyllotaxis = 180 * kDeg;  // distichous
    s.lateralAngle = 50 * kDeg;
    s.gravitropism = 0.04;
    s.phototropism = 0.04;
    s.budBreak = 3.0;
    s.budBreakAgeStart = 0.15;  // little early branching ...
    s.budBreakAgeRate = 0.1;    // ... apical dominance weakens with age
    s.leafSize = 0.06;
    return o;
}

KanayamaOptions azalea() {
    KanayamaOptions o;
    o.preset = "azalea";
    KanayamaSpecies& s = o.species;
    s.branching = KanayamaBranching::Sympodial;
    s.sympodialBend = 25 * kDeg;
    s.alphaTerminal = 0.8;
    s.alphaLateral = 0.7;  // weak apical dominance: bushy
    s.beta = 0.7;
    s.gamma = 0.5;
    s.shortShootNodes = 3;
    s.longShootMaxNodes = 7;
    s.shortInternode = 0.003;
    s.longInternodeMax = 0.019;
    s.longShootVigour = 0.3;
    s.terminalLateralBuds = 3;  // pseudo-whorls below the (flower) terminal bud
    s.lateralBudsPerNode = 1;
    s.phyllotaxis = 144 * kDeg;
    s.lateralAngle = 35 * kDeg;
    s.gravitropism = 0.06;
    s.phototropism = 0.08;
    s.budBreak = 1.0;
    s.leafSize = 0.035;
    s.leavesPerNode = 1;
    s.initialArea = 1.5e-6;
    s.areaPerLeaf = 0.8e-6;
    return o;
}

InputError optionError(const std::string& file, const std::string& where, const std::string& msg) {
    return InputError(file, where, msg);
}

}  // namespace

std::vector<std::string> kanayamaPresetNames() { return {"cherry", "zelkova", "azalea"}; }

KanayamaOptions kanayamaPreset(const std::string& name) {
    if (name == "cherry") return cherry();
    if (name == "zelkova") return zelkova();
    if (name == "azalea") return azalea();
    throw InputError("", "preset",
                     "unknown Kanayama preset '" + name + "'; expected cherry, zelkova or azalea");
}

void validateKanayamaOptions(const KanayamaOptions& o, const std::string& file) {
    if (o.years < 0 || o.years > 500)
        throw optionError(file, "years",
                          "expected an integer in [0, 500], found " + std::to_string(o.years));
    if (o.removeLeaderAtYear < -1 || o.removeLeaderAtYear > 500)
        throw optionError(file, "removeLeaderAtYear", "expected -1 (never) or a year in [0, 500]");
    if (!(o.skyBrightness >= 0 && o.skyBrightness <= 100))
        throw optionError(file, "skyBrightness", "expected a finite number in [0, 100]");
    if (o.skyDirections < 1 || o.skyDirections > 100000)
        throw optionError(file, "skyDirections", "expected an integer in [1, 100000]");
    if (o.threads < 0) throw optionError(file, "threads", "expected an integer >= 0");
    const KanayamaSpecies& s = o.species;
    for (const RealParameter& p : kRealParameters) {
        double v = s.*p.member;
        // NaN fails both comparisons, so it is rejected here too.
        if (!(v >= p.lo && v <= p.hi && !std::isnan(v)))
            throw optionError(file, "species." + jsonName(p),
                              "expected a number in " + formatRange(p.lo, p.hi, p.degrees) +
                                  ", found " + std::to_string(p.degrees ? v / kDeg : v));
    }
    for (const IntParameter& p : kIntParameters) {
        int v = s.*p.member;
        if (v < p.lo || v > p.hi)
            throw optionError(file, std::string("species.") + p.name,
                              "expected an integer in [" + std::to_string(p.lo) + ", " +
                                  std::to_string(p.hi) + "], found " + std::to_string(v));
    }
    if (s.longShootMaxNodes < s.shortShootNodes)
        throw optionError(file, "species.longShootMaxNodes",
                          "expected >= shortShootNodes (a long shoot has at least as many nodes)");
    if (s.beta * s.alphaTerminal >= 1)
        throw optionError(file, "species.alphaTerminal",
                          "expected beta * alphaTerminal < 1 (else a leader's hormone grows "
                          "without bound)");
}

KanayamaOptions readKanayamaOptions(JsonReader& r) {
    KanayamaOptions o =
        kanayamaPreset(r.choice("preset", "cherry", {"cherry", "zelkova", "azalea"}));
    o.seed =
        static_cast<uint64_t>(r.integer("seed", static_cast<long long>(o.seed), 0, (1ll << 53)));
    o.years = static_cast<int>(r.integer("years", o.years, 0, 500));
    o.removeLeaderAtYear =
        static_cast<int>(r.integer("removeLeaderAtYear", o.removeLeaderAtYear, -1, 500));
    o.removeLeaderShoots =
        static_cast<int>(r.integer("removeLeaderShoots", o.removeLeaderShoots, 1, 500));
    o.skyBrightness = r.inRange("skyBrightness", o.skyBrightness, 0, 100);
    o.skyDirections = static_cast<int>(r.integer("skyDirections", o.skyDirections, 1, 100000));
    o.referenceLight = r.boolean("referenceLight", o.referenceLight);
    o.threads = static_cast<int>(r.integer("threads", o.threads, 0, 1024));
    if (auto species = r.object("species")) {
        KanayamaSpecies& s = o.species;
        std::string branching = species->choice(
            "branching", s.branching == KanayamaBranching::Monopodial ? "monopodial" : "sympodial",
            {"monopodial", "sympodial"});
        s.branching = branching == "monopodial" ? KanayamaBranching::Monopodial
                                                : KanayamaBranching::Sympodial;
        for (const RealParameter& p : kRealParameters) {
            double scale = p.degrees ? kDeg : 1;
            double hi = std::isinf(p.hi) ? 1e300 : p.hi / scale;
            s.*p.member =
                species->inRange(jsonName(p), s.*p.member / scale, p.lo / scale, hi) * scale;
        }
        for (const IntParameter& p : kIntParameters)
            s.*p.member = static_cast<int>(species->integer(p.name, s.*p.member, p.lo, p.hi));
        species->finish();
    }
    r.finish();
    validateKanayamaOptions(o, r.file());
    return o;
}

KanayamaOptions readKanayamaOptionsFile(const std::string& path) {
    nlohmann::json json = parseJsonFile(path);
    JsonReader reader(json, path);
    return readKanayamaOptions(reader);
}

}  // namespace nenrin
