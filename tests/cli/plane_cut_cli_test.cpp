// bake slice --origin/--right/--up (issue 30): a cut through any plane equals the named plane
// bakes for the same plane, and bad cuts are refused before anything is written; --finish.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "tests/cli/cli_fixture.h"

namespace nenrin {
namespace {

std::string csv(double x, double y, double z) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g", x, y, z);
    return buf;
}

/// The largest difference between two bakes' samples, over every channel.
double largestDifference(const fs::path& a, const fs::path& b) {
    auto x = readImage(a), y = readImage(b);
    EXPECT_TRUE(x && y);
    if (!x || !y || x->pixels.size() != y->pixels.size()) return INFINITY;
    double worst = 0;
    for (size_t i = 0; i < x->pixels.size(); ++i)
        worst = std::max(worst, double(std::abs(x->pixels[i] - y->pixels[i])));
    return worst;
}

class PlaneCutCliTest : public CliTest {};

TEST_F(PlaneCutCliTest, PlaneCutsEqualTheNamedPlanes) {
    // The same samples: a named plane puts pixel centres in its extent; a cut's outermost
    // samples lie on its edges, so its edges are (n - 1) / n of the extent, half a pixel in.
    const int n = 48;
    const double size = 0.05, px = size / n, edge = size * (n - 1) / n;
    const std::string grain = grainScene("species/hinoki.json").string();
    struct Case {
        const char* plane;
        double at, bottom;
        std::string origin, right, up;
    };
    const Case cases[] = {
        {"tangential", 0.08, 0.975, csv(0.08, -size / 2 + px / 2, 0.975 + px / 2), csv(0, edge, 0),
         csv(0, 0, edge)},
        {"radial", 0.01, 0.975, csv(-size / 2 + px / 2, 0.01, 0.975 + px / 2), csv(edge, 0, 0),
         csv(0, 0, edge)},
        {"cross", 1.0, 0, csv(-size / 2 + px / 2, -size / 2 + px / 2, 1.0), csv(edge, 0, 0),
         csv(0, edge, 0)},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.plane);
        const std::string res = std::to_string(n) + "x" + std::to_string(n);
        auto named = slice({{"--grain", grain},
                            {"--plane", c.plane},
                            {"--at", std::to_string(c.at)},
                            {"--size", "0.05x0.05m"},
                            {"--bottom", std::to_string(c.bottom)},
                            {"--res", res},
                            {"-o", (out_ / "named.exr").string()}});
        ASSERT_EQ(named.exitCode, 0) << named.err;
        auto cut = slice({{"--grain", grain},
                          {"--plane", kOmit},
                          {"--at", kOmit},
                          {"--size", kOmit},
                          {"--origin", c.origin},
                          {"--right", c.right},
                          {"--up", c.up},
                          {"--res", res},
                          {"-o", (out_ / "cut.exr").string()}});
        ASSERT_EQ(cut.exitCode, 0) << cut.err;
        EXPECT_LE(largestDifference(out_ / "named.exr", out_ / "cut.exr"), 1e-6);
    }
}

TEST_F(PlaneCutCliTest, BadPlaneCutsAreRefused) {
    const Options named{{"--plane", kOmit}, {"--at", kOmit}, {"--size", kOmit}};
    auto with = [&](Options extra) {
        for (const auto& kv : named) extra.insert(kv);
        return slice(extra);
    };
    expectInputError(with({{"--origin", "0,0,1"}, {"--right", "0.1,0,0"}}),
                     {"all of --origin, --right and --up"});
    expectInputError(with({{"--origin", "0,0,1"}, {"--right", "0,0,0"}, {"--up", "0,0.1,0"}}),
                     {"--right", "no length"});
    expectInputError(with({{"--origin", "0,0,1"}, {"--right", "0.1,0,0"}, {"--up", "0.2,0,0"}}),
                     {"--up", "parallel"});
    expectInputError(with({{"--origin", "0,nan,1"}, {"--right", "0.1,0,0"}, {"--up", "0,0.1,0"}}),
                     {"--origin"});
    // A cut is instead of a named plane: both at once is a usage error.
    auto both = slice({{"--origin", "0,0,1"}, {"--right", "0.1,0,0"}, {"--up", "0,0.1,0"}});
    EXPECT_NE(both.exitCode, 0);
    EXPECT_NE(both.err.find("excludes"), std::string::npos) << both.err;
    EXPECT_EQ(outputFiles(), std::vector<std::string>{});
}

// --finish sawn: the cut shows saw marks (a sawn sample block); the default, oiled, leaves the
// bake as it was; an unknown finish is refused naming the option and the presets.
TEST_F(PlaneCutCliTest, TheSawnFinishAddsSawMarksToTheCut) {
    const std::string grain = grainScene("species/hinoki.json").string();
    auto bake = [&](const std::string& finish, const std::string& name) {
        return slice({{"--grain", grain},
                      {"--plane", "cross"},
                      {"--size", "0.02x0.02m"},
                      {"--res", "64x64"},
                      {"--finish", finish},
                      {"-o", (out_ / name).string()}});
    };
    ASSERT_EQ(bake(kOmit, "default.exr").exitCode, 0);
    ASSERT_EQ(bake("oiled", "oiled.exr").exitCode, 0);
    ASSERT_EQ(bake("sawn", "sawn.exr").exitCode, 0);
    EXPECT_EQ(largestDifference(out_ / "default.exr", out_ / "oiled.exr"), 0);
    const double marks = largestDifference(out_ / "oiled.exr", out_ / "sawn.exr");
    EXPECT_GT(marks, 0.01);  // saw marks change the colour ...
    EXPECT_LT(marks, 0.5);   // ... by a fraction of it
    for (const char* name : {"default.exr", "oiled.exr", "sawn.exr"}) fs::remove(out_ / name);
    expectInputError(bake("polished", "bad.exr"), {"--finish", "sawn", "polished"});
}

}  // namespace
}  // namespace nenrin
