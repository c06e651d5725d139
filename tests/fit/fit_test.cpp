// The fit from photographs (fit/): the sample file, the ring-start detector, and a round trip:
// six faces baked from a known skeleton and grain, fitted, give back the pith line and the
// ring widths.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "fit/ring_starts.h"
#include "fit/sample_file.h"
#include "fit/wood_fit.h"
#include "grain/grain_params.h"
#include "grain/grown_tree.h"
#include "renderer/bake/bake_specs.h"
#include "renderer/bake/grid_bake.h"
#include "renderer/bake/grid_writers.h"
#include "shader/wood_shader.h"
#include "tests/scratch_path.h"
#include "util/input_error.h"

namespace nenrin {
namespace {

namespace fs = std::filesystem;

const fs::path kMokume = fs::path(NENRIN_SOURCE_DIR) / "../shared/data/mokume";

/// The faces of a 5 cm cube centred at the origin, as the Mokume samples lay them out.
struct CubeFace {
    const char* name;
    Vec3 origin, right, up;
};
const CubeFace kCube[6] = {{"A", {-0.025, -0.025, 0.025}, {0.05, 0, 0}, {0, 0.05, 0}},
                           {"B", {-0.025, 0.025, 0.025}, {0.05, 0, 0}, {0, 0, -0.05}},
                           {"C", {-0.025, -0.025, -0.025}, {0, 0, 0.05}, {0, 0.05, 0}},
                           {"D", {-0.025, -0.025, -0.025}, {0.05, 0, 0}, {0, 0, 0.05}},
                           {"E", {0.025, -0.025, 0.025}, {0, 0, -0.05}, {0, 0.05, 0}},
                           {"F", {0.025, -0.025, -0.025}, {-0.05, 0, 0}, {0, 0.05, 0}}};

nlohmann::json faceJson(const CubeFace& f, const std::string& image) {
    return {{"name", f.name},
            {"image", image},
            {"origin", {f.origin.x, f.origin.y, f.origin.z}},
            {"right", {f.right.x, f.right.y, f.right.z}},
            {"up", {f.up.x, f.up.y, f.up.z}}};
}

void writeJson(const fs::path& path, const nlohmann::json& j) { std::ofstream(path) << j.dump(1); }

/// The Mokume photographs live beside the repository (../shared/data/mokume); a clone on its
/// own has none.
#define SKIP_WITHOUT_MOKUME()                     \
    if (!fs::exists(kMokume / "H11/sample.json")) \
    GTEST_SKIP() << "no Mokume photographs at " << kMokume << " (../shared/data/mokume)"

// ---- the sample file ----

TEST(SampleFile, ReadsTheMokumeCubes) {
    SKIP_WITHOUT_MOKUME();
    const Sample s = loadSampleFile((kMokume / "H11/sample.json").string());
    ASSERT_EQ(s.faces.size(), 6u);
    EXPECT_EQ(s.faces[2].name, "C");
    EXPECT_TRUE(fs::exists(s.faces[2].image));
    ASSERT_TRUE(s.faces[2].rings.has_value());
    // The README's convention: the bottom-left corner is `origin`, the top-right origin +
    // right + up; right x up points out of the cube.
    const Vec3 topRight = s.faces[0].at(1, 0);
    EXPECT_NEAR(topRight.x, 0.025, 1e-12);
    EXPECT_NEAR(topRight.y, 0.025, 1e-12);
    EXPECT_NEAR(s.faces[0].normal().z, 1, 1e-12);
    EXPECT_NEAR(s.faces[1].normal().y, 1, 1e-12);  // B: y = +25 mm
}

TEST(SampleFile, NamesTheFileAndPlaceOfEachMistake) {
    const ScratchFolder folder("fit-sample-errors");
    const fs::path& dir = folder.path();
    const std::string image =
        (fs::path(NENRIN_SOURCE_DIR) / "tests/data/ref/table-top-closeup-4096spp.png").string();
    auto expectError = [&](const nlohmann::json& j, const std::string& where,
                           const std::string& what) {
        writeJson(dir / "s.json", j);
        try {
            loadSampleFile((dir / "s.json").string());
            ADD_FAILURE() << "accepted: " << j.dump();
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("s.json"), std::string::npos) << e.what();
            EXPECT_EQ(e.where(), where) << e.what();
            EXPECT_NE(e.message().find(what), std::string::npos) << e.what();
        }
    };
    const nlohmann::json face = faceJson(kCube[0], image);
    auto with = [&](const char* key, nlohmann::json value) {
        nlohmann::json f = face;
        f[key] = value;
        return nlohmann::json{{"size", {0.05, 0.05, 0.05}}, {"faces", {f}}};
    };
    expectError({{"size", {0.05, 0.05, 0.05}}, {"faces", nlohmann::json::array()}}, "faces",
                "at least one");
    expectError({{"size", {0.05, 0.05}}, {"faces", {face}}}, "size", "three edges");
    expectError({{"size", {0.05, 0.05, 1e308}}, {"faces", {face}}}, "size[2]", "beyond");
    expectError({{"size", {0.05, 0.05, 20}}, {"faces", {face}}}, "size", "1 mm to 10 m");
    expectError(with("image", "missing.png"), "faces[0].image", "no such image");
    expectError(with("image", std::string(300, 'x') + ".png"), "faces[0].image",
                "no such image");  // a name too long for the system: once a filesystem throw
    expectError(with("right", {0, 0, 0}), "faces[0].right", "1 mm to 10 m");
    expectError(with("up", {0.05, 0, 0}), "faces[0].up", "across");
    expectError(with("rihgt", {0.05, 0, 0}), "faces[0].rihgt", "unknown key");
    expectError(with("origin", {0, "x", 0}), "faces[0].origin[1]", "");
}

// ---- the ring starts ----

/// Rings starting at `starts` (samples): within each ring lightness falls linearly from
/// `early` to `late` wood, then jumps back at the next start (a conifer's rise); with
/// `porous`, the ring starts with a dark band of pores instead (a fall).
std::vector<double> ringProfile(const std::vector<int>& starts, int length, bool porous) {
    std::vector<double> L(size_t(length), 70.0);
    std::mt19937 random(5);
    std::normal_distribution<double> texture(0, 0.8);
    for (size_t k = 0; k + 1 < starts.size(); ++k)
        for (int i = starts[k]; i < starts[k + 1]; ++i) {
            const double u = double(i - starts[k]) / (starts[k + 1] - starts[k]);
            // Pores: a sharp start, fading into the late wood over a quarter of the ring.
            L[size_t(i)] =
                porous ? 55 + 20 * std::clamp((u - 0.15) / 0.25, 0.0, 1.0) : 82 - 20 * u * u * u;
        }
    for (double& v : L) v += texture(random);
    return L;
}

TEST(RingStarts, FindsEachRingsEdgeInConifersAndRingPorousWood) {
    const std::vector<int> starts = {10, 52, 95, 128, 175, 214, 262, 300, 335};
    for (bool porous : {false, true}) {
        const std::vector<int> found = ringStarts(ringProfile(starts, 340, porous), 40);
        // The first and last starts lie where the profile begins and ends: the edges between.
        ASSERT_GE(found.size(), starts.size() - 2) << (porous ? "porous" : "conifer");
        size_t matched = 0;
        for (int s : std::vector<int>(starts.begin() + 1, starts.end() - 1))
            for (int f : found) matched += std::abs(f - s) <= 1;
        EXPECT_EQ(matched, starts.size() - 2) << (porous ? "porous" : "conifer");
    }
}

TEST(RingStarts, DoesNotSplitARingPorousRingAtItsSecondRowOfPores) {
    // Chestnut's early wood: a dark row of large pores at the ring's start and a fainter
    // second row halfway through, whose fall is a third of the first's (CN03's profiles
    // swing twice a ring: its rings were counted 2.3 times over, each fall half a period from
    // a stronger one making a ring start).
    const std::vector<int> starts = {10, 52, 95, 128, 175, 214, 262, 300, 335};
    std::vector<double> L = ringProfile(starts, 340, true);
    for (size_t k = 0; k + 1 < starts.size(); ++k) {
        const int second = starts[k] + int(0.5 * (starts[k + 1] - starts[k]));
        for (int i = second; i < second + 5; ++i) L[size_t(i)] -= 7;
    }
    // The profile's swings count half the rings' period, 20 samples, or the whole, 40.
    for (double period : {20.0, 40.0}) {
        const std::vector<int> found = ringStarts(L, period);
        size_t matched = 0;
        for (int s : std::vector<int>(starts.begin() + 1, starts.end() - 1))
            for (int f : found) matched += std::abs(f - s) <= 1;
        EXPECT_EQ(matched, starts.size() - 2) << "period " << period;
        EXPECT_LE(found.size(), starts.size()) << "period " << period;
    }
}

// ---- the round trip ----

/// Six faces of a 5 cm cube baked from a straight trunk 70 mm from the cube's centre,
/// slightly tilted, with a ring series of 2.5-4 mm rings, as PNG photographs.
struct SyntheticSample {
    fs::path file;
    Vec3 pithAtY0{-0.06, 0, 0.035}, direction = normalize(Vec3{0.02, 2, 0.01});
    std::vector<double> widths;
    /// With a knot: a branch from the pith 12 mm below the cube's centre, rising through faces
    /// C (x = -25 mm) and F (z = -25 mm), growing out slowly (year 7 at C), gamma 0.3.
    bool knot = false;
    Vec3 branchStart() const { return pithAtY0 + direction * (-0.012 / direction.y); }
    Vec3 branchDirection() const { return normalize(Vec3{1, 0.25, -1}); }
};

/// The synthetic branch: m long, its tip there in this year (it grows out at a steady pace).
constexpr double kBranchLength = 0.15, kBranchBirthAtEnd = 21;

/// Where the branch crosses the plane through `origin` with normal `n`.
Vec3 branchCrossing(const SyntheticSample& s, const Vec3& origin, const Vec3& n) {
    const Vec3 u = s.branchDirection();
    return s.branchStart() + u * (dot(origin - s.branchStart(), n) / dot(u, n));
}

/// The hinoki preset with its knots' late-wood darkening set to `ringDarkening`, and without
/// its knots' halo unless `keepHalo`.
nlohmann::json hinokiWith(double ringDarkening, bool keepHalo = false) {
    nlohmann::json grain = nlohmann::json::parse(
        std::ifstream(fs::path(NENRIN_SOURCE_DIR) / "scenes/grain/species/hinoki.json"));
    grain["colour"]["knots"]["ring_darkening"] = ringDarkening;
    if (!keepHalo) grain["colour"]["knots"]["halo_tint"] = {1, 1, 1};
    return grain;
}

/// The cube baked with hinoki's colours and anatomy (its knots' late wood darkened by
/// `knotRingDarkening`, `knotColours` set in its `colour.knots`).
SyntheticSample bakeSyntheticSample(const fs::path& dir, bool knot = false,
                                    double knotRingDarkening = 0,
                                    const nlohmann::json& knotColours = nlohmann::json::object()) {
    SyntheticSample s;
    s.knot = knot;
    std::mt19937 random(3);
    std::uniform_real_distribution<double> width(0.0025, 0.004);
    for (int year = 0; year < 60; ++year) s.widths.push_back(width(random));
    Skeleton skeleton;
    skeleton.addTrunk({s.pithAtY0 - s.direction * 1.0, s.pithAtY0 + s.direction * 1.0}, {0, 0});
    skeleton.setRingWidths(s.widths);
    if (knot) {
        ChainProperties props;
        props.gamma = 0.3;
        skeleton.addBranch(0,
                           {s.branchStart(), s.branchStart() + s.branchDirection() * kBranchLength},
                           {0, kBranchBirthAtEnd}, props);
    }
    // Hinoki's colours and anatomy, its ring shapes off: the rings are cylinders, the knot's
    // circles (with the preset's wobble of 0.5 years the finder reads F's knot 18 mm off,
    // at 0.25 years 2.3 mm: a knot whose faint rings wobble is no longer found by them).
    nlohmann::json grain = hinokiWith(knotRingDarkening);
    grain["colour"]["knots"].update(knotColours);
    grain["colour"]["knots"].erase("ring_wobble");
    for (const char* key : {"sway", "wander", "direction", "rings"}) grain.erase(key);
    const GrownTree tree(Skeleton(skeleton), parseGrain(grain, "hinoki"));
    const WoodShader shader(tree.field());
    nlohmann::json faces = nlohmann::json::array();
    for (const CubeFace& f : kCube) {
        SliceSpec spec;
        spec.cut = PlaneCut{f.origin, f.right, f.up};
        spec.resX = spec.resY = 256;
        BakedGrid grid = sliceGrid(skeleton, spec);
        bakeGrid(shader, grid, {2, true, "test"});
        const std::string image = std::string(f.name) + ".png";
        writeSlicePreviewPng(grid, (dir / image).string());
        faces.push_back(faceJson(f, image));
    }
    s.file = dir / "sample.json";
    writeJson(s.file, {{"size", {0.05, 0.05, 0.05}}, {"faces", faces}});
    return s;
}

TEST(WoodFit, RecoversThePithAndTheRingWidthsOfABakedCube) {
    const ScratchFolder folder("fit-round-trip");
    const SyntheticSample truth = bakeSyntheticSample(folder.path());
    const Sample sample = loadSampleFile(truth.file.string());
    FitOptions options;
    options.threads = 2;
    const WoodFit fit = fitSample(sample, options);

    // The pith line: within 1 mm across it at the cube's centre, and its direction.
    const Vec3 q = truth.pithAtY0 - fit.pith.point;
    const Vec3 across = q - fit.pith.direction * dot(q, fit.pith.direction);
    EXPECT_LT(length(across), 0.001) << "pith off by " << length(across) * 1e3 << " mm";
    EXPECT_GT(std::abs(dot(fit.pith.direction, truth.direction)), std::cos(0.5 * M_PI / 180));

    // The ring boundaries: the true ones (cumulative widths) in the measured range, each found
    // within 0.3 mm once the radii's common offset is taken out (a tenth of a millimetre of
    // pith error moves them all), and the widths between found neighbours within 10 %.
    std::vector<double> boundaries{0};
    for (double w : truth.widths) boundaries.push_back(boundaries.back() + w);
    const std::vector<double>& found = fit.profile.boundaries;
    ASSERT_GE(found.size(), 8u);
    auto nearestTrue = [&](double r) {
        double best = 1;
        for (double b : boundaries)
            if (std::abs(r - b) < std::abs(best)) best = r - b;
        return best;
    };
    std::vector<double> offsets;
    for (double f : found) offsets.push_back(nearestTrue(f));
    std::nth_element(offsets.begin(), offsets.begin() + long(offsets.size() / 2), offsets.end());
    const double offset = offsets[offsets.size() / 2];
    EXPECT_LT(std::abs(offset), 1e-3);
    int inside = 0, matched = 0, widthsChecked = 0;
    for (size_t y = 0; y < boundaries.size(); ++y) {
        const double r = boundaries[y] + offset;
        if (r < found.front() - 1e-4 || r > found.back() + 1e-4) continue;
        ++inside;
        for (size_t k = 0; k < found.size(); ++k)
            if (std::abs(found[k] - r) < 3e-4) {
                ++matched;
                if (k + 1 < found.size() && y + 1 < boundaries.size() &&
                    std::abs(found[k + 1] - (boundaries[y + 1] + offset)) < 3e-4) {
                    EXPECT_NEAR(found[k + 1] - found[k], truth.widths[y], 0.1 * truth.widths[y]);
                    ++widthsChecked;
                }
            }
    }
    // (Narrow rings beside wide ones can show too weak an edge: 2 of 19 are missed today.)
    EXPECT_GE(matched, 0.85 * inside) << "of " << inside << " ring boundaries";
    EXPECT_GE(widthsChecked, 10);

    // Baked through the fit, every face's rings run as the photo's.
    for (const FaceFigures& f : fit.faces) EXPECT_LT(f.ringMedianDeg, 3) << "face " << f.name;
    // A cube without knots gets no branch.
    EXPECT_TRUE(fit.branches.empty());
    EXPECT_TRUE(fit.knots.empty());
}

/// Two threads, quiet, the anatomy (and the knots' junction) of `base` (the hinoki preset).
FitOptions hinokiOptions(const fs::path& base = fs::path(NENRIN_SOURCE_DIR) /
                                                "scenes/grain/species/hinoki.json") {
    FitOptions options;
    options.threads = 2;
    options.quiet = true;
    options.baseGrains = {base.string()};
    return options;
}

/// The cube with a knot baked with `truthDarkening` (the knots' late-wood darkening), fitted
/// from the hinoki preset with `baseDarkening`: the branch in place and sized, the faces' rings
/// as baked, the knot wood's ring contrast matched. Returns the fit.
WoodFit expectBakedKnotFitted(const std::string& name, double truthDarkening,
                              double baseDarkening) {
    const ScratchFolder folder("fit-" + name), baseFolder("fit-" + name + "-base");
    const SyntheticSample truth = bakeSyntheticSample(folder.path(), true, truthDarkening);
    const Sample sample = loadSampleFile(truth.file.string());
    const fs::path base = baseFolder.path() / "hinoki.json";
    writeJson(base, hinokiWith(baseDarkening, true));
    // The knot's flanks are the junction's (eq. 5): from the grain it was baked with.
    WoodFit fit = fitSample(sample, hinokiOptions(base));
    // The preset's knot ring wobble, left out of the fit's bakes, is in the grain it writes.
    EXPECT_EQ(fit.grain["colour"]["knots"].value("ring_wobble", 0.0),
              hinokiWith(0)["colour"]["knots"].value("ring_wobble", -1.0));
    EXPECT_EQ(fit.branches.size(), 1u);
    if (fit.branches.size() != 1) return fit;
    EXPECT_EQ(fit.branches[0].faces.size(), 2u) << "one branch through both faces";
    EXPECT_EQ(fit.knots.size(), 2u) << "the knot is seen on C and F and nowhere else";
    for (const KnotFigures& k : fit.knots) {
        EXPECT_TRUE(k.photo.face == "C" || k.photo.face == "F") << k.photo.face;
        const CubeFace& f = k.photo.face == "C" ? kCube[2] : kCube[5];
        const Vec3 crossing = branchCrossing(truth, f.origin, normalize(cross(f.right, f.up)));
        // The knot's rings centre near where the branch crosses (a branch growing out slowly
        // has eccentric rings, their centres towards the pith: 3-4 mm here) ...
        EXPECT_LT(length(k.photo.centre - crossing), 0.005) << "face " << f.name;
        // ... and the fitted branch bakes its knot onto the photographed one.
        EXPECT_TRUE(k.baked.has_value()) << "face " << f.name;
        if (k.baked) {
            EXPECT_LT(k.offsetMm, 1.0) << "face " << f.name;
        }
    }
    // The faces the branch does not reach as without a knot, the knot's two within 15 deg.
    // (E, which the branch passes just outside, is not held: its flank there depends on
    // gamma, measured 0.37 against 0.3 from the knot's faint rings: 25 deg today.) The ring
    // series is read where no knot is, so its widths are the trunk's.
    for (const FaceFigures& f : fit.faces) {
        if (f.name == "A" || f.name == "B" || f.name == "D") {
            EXPECT_LT(f.ringMedianDeg, 5) << "face " << f.name;
        } else if (f.name == "C" || f.name == "F") {
            EXPECT_LT(f.ringMedianDeg, 15) << "face " << f.name;
        }
    }
    // The knot's size: the branch's birth where it crosses the face that sized it (year 7 at
    // C, 12 at F: the branch crosses both equally squarely, so either may), from the knot's
    // radius.
    const CubeFace& sizer = fit.branches[0].sizedBy == "C" ? kCube[2] : kCube[5];
    const double path =
        length(branchCrossing(truth, sizer.origin, normalize(cross(sizer.right, sizer.up))) -
               truth.branchStart());
    EXPECT_NEAR(fit.branches[0].birth, kBranchBirthAtEnd * path / kBranchLength, 1.0)
        << "sized by " << fit.branches[0].sizedBy;
    // The knot wood's rings as contrasted as baked.
    EXPECT_NEAR(fit.knotRings.baked, fit.knotRings.photo, 0.1 * fit.knotRings.photo);
    const std::vector<double>& b = fit.profile.boundaries;
    EXPECT_GE(b.size(), 4u);
    if (b.size() >= 4) {
        EXPECT_GT((b.back() - b.front()) / double(b.size() - 1), 0.0025);
        EXPECT_LT((b.back() - b.front()) / double(b.size() - 1), 0.004);
    }
    return fit;
}

double ringDarkening(const WoodFit& fit) {
    return fit.grain["colour"]["knots"].value("ring_darkening", 0.0);
}

/// The fitted grain's halo tint (white without one).
Rgb haloTint(const WoodFit& fit) {
    const nlohmann::json& knots = fit.grain["colour"]["knots"];
    if (!knots.contains("halo_tint")) return {1, 1, 1};
    const nlohmann::json& t = knots["halo_tint"];
    return {t[0].get<double>(), t[1].get<double>(), t[2].get<double>()};
}

TEST(WoodFit, PutsTheBranchOfABakedKnotThroughBothFacesItCrosses) {
    // A knot whose late wood is no darker than the stem's, fitted from the preset (0.25):
    // the darkening is taken out, none invented; nor a halo (the preset's is the fit's to
    // find, step 10) where the bake has none.
    const WoodFit fit = expectBakedKnotFitted("knot", 0, 0.25);
    EXPECT_LT(ringDarkening(fit), 0.1);
    EXPECT_FALSE(fit.halo.kept);
    EXPECT_EQ(haloTint(fit).b, 1.0);
}

TEST(WoodFit, FindsTheOrangeHaloRoundABakedKnot) {
    // The knot cube baked with an orange halo 6 mm wide, three times that along the stem,
    // fitted from the hinoki preset (its own halo, H11's, left out): the reach and the tint
    // are found (the tint a little light: it is fitted against bakes whose colours were
    // calibrated to the stained photographs), and every face's colour matches.
    const ScratchFolder folder("fit-halo");
    const Rgb truth{0.8, 0.6, 0.45};
    const SyntheticSample baked = bakeSyntheticSample(
        folder.path(), true, 0.25,
        {{"halo_tint", {truth.r, truth.g, truth.b}}, {"halo_width", 0.006}, {"halo_axial", 3}});
    const WoodFit fit = fitSample(loadSampleFile(baked.file.string()), hinokiOptions());
    ASSERT_TRUE(fit.halo.kept);
    EXPECT_EQ(fit.halo.width, 0.006);
    EXPECT_EQ(fit.halo.axial, 3);
    const Rgb tint = haloTint(fit);
    EXPECT_NEAR(tint.r, truth.r, 0.08);
    EXPECT_NEAR(tint.g, truth.g, 0.08);
    EXPECT_NEAR(tint.b, truth.b, 0.08);
    for (const FaceFigures& f : fit.faces) EXPECT_LT(f.dE, 2.5) << "face " << f.name;
}

TEST(WoodFit, FindsTheDarkRingsOfABakedKnot) {
    // The preset's knot (late wood darkened 0.25, as fitted to the photographed hinoki knot),
    // fitted from a grain without: the darkening is found.
    const WoodFit fit = expectBakedKnotFitted("dark-knot", 0.25, 0);
    EXPECT_NEAR(ringDarkening(fit), 0.25, 0.1);
}

TEST(WoodFit, PutsTheKnotOfHinokiH11WhereThePhotosShowIt) {
    SKIP_WITHOUT_MOKUME();
    const Sample sample = loadSampleFile((kMokume / "H11/sample.json").string());
    const WoodFit fit = fitSample(sample, hinokiOptions());
    // One branch through both faces the knot crosses (marked in C_knot.png and F_knot.png).
    ASSERT_EQ(fit.branches.size(), 1u);
    EXPECT_EQ(fit.branches[0].faces.size(), 2u);
    ASSERT_EQ(fit.knots.size(), 2u) << "the knot is seen on C and F and nowhere else";
    // Its rings' contrast as photographed (the preset's ring darkening, 0.25, is this fit's).
    EXPECT_NEAR(fit.knotRings.baked, fit.knotRings.photo, 0.1 * fit.knotRings.photo);
    EXPECT_GT(fit.grain["colour"]["knots"].value("ring_darkening", 0.0), 0.1);
    for (const KnotFigures& k : fit.knots) {
        ASSERT_TRUE(k.photo.face == "C" || k.photo.face == "F") << k.photo.face;
        const double markColumn = k.photo.face == "C" ? 71 : 142;
        const double markRow = k.photo.face == "C" ? 184 : 207;
        const double mmPerPixel = 50.0 / 255;
        ASSERT_TRUE(k.baked.has_value()) << "face " << k.photo.face;
        // The bake's knot within 3 mm of the mark (the bound) and within 1 mm of the
        // knot the fit saw in the photo.
        EXPECT_LT(std::hypot(k.baked->column - markColumn, k.baked->row - markRow) * mmPerPixel,
                  3.0)
            << "face " << k.photo.face;
        EXPECT_LT(k.offsetMm, 1.0) << "face " << k.photo.face;
    }
}

TEST(WoodFit, PlacesTheLeftOutEndFaceOfH11ByTheOtherFacesRingPatterns) {
    // H11's pith runs along y: B and D are its end faces, A, C, E and F lie along it and show
    // every ring as a line wherever the pith is. With B left out only D's rings are arcs, and
    // they wave more than they curve: the ring directions put the pith 2 m off and B measured
    // 34 degrees. The ring patterns of the faces agree where the pith really is (cross-dating,
    // fit/cross_dating.h): the pith comes within 40 mm of the sample and B measures 9.
    SKIP_WITHOUT_MOKUME();
    const Sample sample = loadSampleFile((kMokume / "H11/sample.json").string());
    FitOptions options = hinokiOptions();
    options.heldOut = {"B"};
    const WoodFit fit = fitSample(sample, options);
    EXPECT_LT(fit.pith.distance, 0.1);
    EXPECT_NEAR(fit.pith.direction.y, 1, 0.01);
    const auto b = std::find_if(fit.faces.begin(), fit.faces.end(),
                                [](const FaceFigures& f) { return f.name == "B"; });
    ASSERT_NE(b, fit.faces.end());
    EXPECT_TRUE(b->heldOut);
    EXPECT_LT(b->ringMedianDeg, 15) << "the issue allows 20 for any face left out";
}

TEST(WoodFit, MatchesTheChestnutCubesColourAndFineTextureOnEveryFace) {
    // The figures for the fitted faces: dE*ab at most 5, fine texture 0.7-1.4 x the
    // photo's. With the chestnut preset's strengths face D (end grain, dense pores) measured
    // fine 0.55 and dE 4.6, B fine 0.69 and F dE 5.4; the fitted end-grain tint and texture
    // strengths bring them in (D 2.2 / 0.81, B 2.7 / 1.02, F 4.3 / 1.00 when written). Mid
    // texture: since the rings are counted as the photographs show them (10, not 22) they
    // carry the pore bands' contrast, twice over until the anatomy's tone was taken out of the
    // ring profile (side faces then up to 1.43, F; now 0.83-1.16). The two end faces' own
    // ring contrast differs by 2 x, which one grain cannot follow (B 1.51, D 0.74).
    SKIP_WITHOUT_MOKUME();
    const Sample sample = loadSampleFile((kMokume / "CN03/sample.json").string());
    const WoodFit fit = fitSample(
        sample, hinokiOptions(fs::path(NENRIN_SOURCE_DIR) / "scenes/grain/species/chestnut.json"));
    ASSERT_EQ(fit.faces.size(), 6u);
    for (const FaceFigures& f : fit.faces) {
        EXPECT_LE(f.dE, 5) << "face " << f.name;
        EXPECT_GE(f.fineRatio, 0.7) << "face " << f.name;
        EXPECT_LE(f.fineRatio, 1.4) << "face " << f.name;
        const bool end = f.name == "B" || f.name == "D";
        EXPECT_GE(f.midRatio, end ? 0.6 : 0.7) << "face " << f.name;
        EXPECT_LE(f.midRatio, end ? 1.6 : 1.4) << "face " << f.name;
    }
    // End grain photographs darker than side grain (Hirata et al. 2020): the fitted tint.
    const ColourParams c = parseGrain(fit.grain, "fitted").colour;
    EXPECT_LT(c.endGrainTint.g, 0.85);
    EXPECT_GT(fit.texture.endCells, 1.1);
}

}  // namespace
}  // namespace nenrin
