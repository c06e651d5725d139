// The anatomy's tones along the wood's own colour line (grain `anatomy.colour_line`): the
// luminance a grey change gives, the hue of darker wood, and, with the option off, the grey
// filter's bits.

#include "shader/colour_line.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "grain/grain_params.h"
#include "shader/wood_shader.h"
#include "skeleton/skeleton_index.h"
#include "tests/test_trees.h"
#include "util/input_error.h"

namespace nenrin {
namespace {

const Rgb kHinokiEarly{0.84, 0.58, 0.44}, kHinokiLate{0.66, 0.40, 0.28};

TEST(ColourLine, DarkerHinokiLosesBlueMostAndRedLeast) {
    const Rgb line = woodColourLine(kHinokiEarly, kHinokiLate);
    // ln(late / early) per channel over its luminance-weighted mean: 0.69, 1.06, 1.29.
    EXPECT_NEAR(line.r, 0.69, 0.01);
    EXPECT_NEAR(line.g, 1.06, 0.01);
    EXPECT_NEAR(line.b, 1.29, 0.01);
    EXPECT_NEAR(luminance(line), 1.0, 1e-12);
}

TEST(ColourLine, GreyWhereLateWoodIsEarlyWoodDarkenedAlike) {
    const Rgb proportional = woodColourLine({0.6, 0.4, 0.3}, {0.48, 0.32, 0.24});
    for (double c : {proportional.r, proportional.g, proportional.b}) EXPECT_NEAR(c, 1.0, 1e-9);
    // Hardly any change in luminance: no direction to read, grey exactly.
    const Rgb same = woodColourLine({0.6, 0.4, 0.3}, {0.61, 0.39, 0.3});
    EXPECT_EQ(same.r, 1.0);
    EXPECT_EQ(same.g, 1.0);
    EXPECT_EQ(same.b, 1.0);
    // A channel that brightens in the late wood is held at half the mean change.
    const Rgb odd = woodColourLine({0.6, 0.4, 0.3}, {0.3, 0.2, 0.35});
    EXPECT_EQ(odd.b, 0.5);
}

TEST(ColourLine, KeepsTheLuminanceOfTheGreyChangeAndSaturatesDarkerWood) {
    const Rgb line = woodColourLine(kHinokiEarly, kHinokiLate);
    std::mt19937 random(5);
    std::uniform_real_distribution<double> channel(0.2, 0.9), brightness(0.6, 1.4);
    for (int i = 0; i < 1000; ++i) {
        const Rgb albedo{channel(random), channel(random), channel(random)};
        const double b = brightness(random);
        AnatomySample a;
        a.brightness = b;
        const Rgb toned = alongColourLine(albedo, a, line);
        EXPECT_NEAR(luminance(toned), b * luminance(albedo), 1e-12) << i;
        // Darker: blue falls further than red (the wood's own hue deepens), lighter the reverse.
        const double warmer = (toned.r / toned.b) / (albedo.r / albedo.b);
        if (b < 0.99) {
            EXPECT_GT(warmer, 1) << i;
        }
        if (b > 1.01) {
            EXPECT_LT(warmer, 1) << i;
        }
    }
}

TEST(ColourLine, AGreyLineIsTheGreyFilterBitForBit) {
    const Rgb albedo{0.7, 0.45, 0.3}, pores{0.6, 0.7, 0.8};
    for (double b : {0.0, 0.5, 1.0, 1.3, -0.2}) {
        AnatomySample a;
        a.brightness = b;
        a.pores = pores;
        const Rgb toned = alongColourLine(albedo, a, {1, 1, 1});
        EXPECT_EQ(toned.r, albedo.r * std::max(0.0, b * pores.r));
        EXPECT_EQ(toned.g, albedo.g * std::max(0.0, b * pores.g));
        EXPECT_EQ(toned.b, albedo.b * std::max(0.0, b * pores.b));
    }
}

TEST(ColourLine, TheShadersHinokiTextureKeepsItsLuminanceAndTakesTheWoodsHue) {
    // The same hinoki-coloured textured wood with the option off and on: every pixel's
    // luminance the same, the texture's darker pixels warmer than the grey filter leaves them.
    const Skeleton skeleton = test::straightTrunk(10, 0.5);
    const SkeletonIndex index(skeleton);
    GrainParams grain;
    grain.radialSpeed = 0.004;
    grain.colour.earlyWood = kHinokiEarly;
    grain.colour.lateWood = kHinokiLate;
    grain.anatomy.enabled = true;
    grain.anatomy.speckleAmplitude = 0.5;
    grain.anatomy.streakAmplitude = 0.1;
    std::vector<Vec3> points;
    for (int k = 0; k < 2000; ++k)
        points.push_back({0.05 + 0.00005 * (k % 40), 0.02, 1 + 0.00005 * (k / 40)});
    std::vector<SurfaceFootprint> f(points.size(), {{}, {}, 0.0001, {0, 1, 0}});
    auto shade = [&](bool colourLine) {
        grain.anatomy.colourLine = colourLine;
        const GrowthField field(index, grain);
        const WoodShader shader(field);
        std::vector<WoodSurfaceSample> out(points.size());
        WoodScratch scratch;
        shader.evaluateSurface(points, f, out, scratch);
        return out;
    };
    const std::vector<WoodSurfaceSample> grey = shade(false), toned = shade(true);
    int darker = 0, warmer = 0, unclamped = 0;
    auto below1 = [](const Rgb& c) { return c.r < 1 && c.g < 1 && c.b < 1; };
    for (size_t i = 0; i < points.size(); ++i) {
        // (The shader holds a reflectance at most 1 per channel: there the two part.)
        if (below1(grey[i].albedo) && below1(toned[i].albedo)) {
            ++unclamped;
            EXPECT_NEAR(luminance(toned[i].albedo), luminance(grey[i].albedo),
                        1e-12 * luminance(grey[i].albedo))
                << i;
        }
        EXPECT_EQ(toned[i].T, grey[i].T);
        // Below the untextured colour's luminance: the texture darkened it.
        const Rgb plain = mix(kHinokiEarly, kHinokiLate, toned[i].lateWood);
        if (luminance(grey[i].albedo) < 0.95 * luminance(plain)) {
            ++darker;
            warmer += toned[i].albedo.r / toned[i].albedo.b > grey[i].albedo.r / grey[i].albedo.b;
        }
    }
    EXPECT_GT(unclamped, 1500);
    EXPECT_GT(darker, 100) << "the case has texture";
    EXPECT_EQ(warmer, darker);
}

TEST(ColourLine, GrainFilesSwitchItOnAndWriteItBack) {
    const GrainParams on = parseGrain({{"anatomy", {{"colour_line", true}}}}, "g.json");
    EXPECT_TRUE(on.anatomy.enabled);
    EXPECT_TRUE(on.anatomy.colourLine);
    EXPECT_TRUE(parseGrain(grainToJson(on), "g.json").anatomy.colourLine);
    // Off (the default): not written, so grain files written before it stay as they were.
    const GrainParams off = parseGrain({{"anatomy", nlohmann::json::object()}}, "g.json");
    EXPECT_FALSE(off.anatomy.colourLine);
    EXPECT_FALSE(grainToJson(off)["anatomy"].contains("colour_line"));
    try {
        parseGrain({{"anatomy", {{"colour_line", 1}}}}, "g.json");
        ADD_FAILURE() << "accepted a number";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("colour_line"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace nenrin
