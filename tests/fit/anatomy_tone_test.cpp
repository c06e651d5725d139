#include "fit/anatomy_tone.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace nenrin {
namespace {

/// A 64 x 64 bake whose rings run across it, four to a row (T = x / 16 years), its colour
/// grey `base` times `darkening(phase)`; the right quarter is knot wood.
template <class Darkening>
FaceFigures bake(double base, Darkening darkening, bool heldOut = false) {
    FaceFigures f;
    f.heldOut = heldOut;
    f.bake.width = f.bake.height = 64;
    f.bake.data.assign(size_t(64 * 64 * BakedGrid::kChannels), 0.0f);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            float* v = f.bake.at(x, y);
            const double t = x / 16.0 + 1e-6, phase = t - std::floor(t);
            const bool knot = x >= 48;
            const double grey = base * (knot ? 0.3 : darkening(phase));
            v[0] = v[1] = v[2] = float(grey);
            v[3] = 1;
            v[4] = float(t);
            v[5] = knot ? 1.0f : 0.0f;
        }
    return f;
}

TEST(AnatomyTone, IsTheAnatomysDarkeningByRingPhaseLessItsMean) {
    // Pores darken the first quarter of every ring to 0.8; the rest of the ring is as
    // without. Knot wood (0.3) and a held-out face (darkened everywhere) are left out.
    auto pores = [](double phase) { return phase < 0.25 ? 0.8 : 1.0; };
    auto none = [](double) { return 1.0; };
    const std::vector<FaceFigures> with = {bake(0.5, pores),
                                           bake(
                                               0.5, [](double) { return 0.1; }, true)};
    const std::vector<FaceFigures> without = {bake(0.5, none), bake(0.5, none, true)};
    const std::vector<double> tone = anatomyTone(with, without, 17);
    ASSERT_EQ(tone.size(), 17u);
    // Phases k / 16: 0.0 ... 0.1875 in the pores (4 of 16 samples a ring), the rest not.
    double mean = 0;
    for (size_t k = 0; k < 16; ++k) mean += tone[k] / 16;
    for (size_t k = 0; k < 17; ++k) {
        const double phase = double(k) / 16;
        if (k == 16) {  // no pixel at phase 1 (T = x / 16 puts them all at 0): left as it is
            EXPECT_EQ(tone[k], 1.0);
            continue;
        }
        EXPECT_NEAR(tone[k] / tone[8], phase < 0.25 ? 0.8 : 1.0, 1e-6) << "phase " << phase;
    }
    EXPECT_NEAR(mean, 1.0, 0.01);
}

TEST(AnatomyTone, DividesTheProfilesColourByIt) {
    nlohmann::json grain = {{"colour",
                             {{"early_wood", {0.6, 0.6, 0.6}},
                              {"late_wood", {0.4, 0.4, 0.4}},
                              {"late_wood_profile", {0.9, 0.5, 0.1}}}}};
    // The first phase's measured colour (0.42) holds pores darkening it to 0.84 of the mean:
    // without them it is 0.5, E 0.5. The last (0.58), darkened to 0.9 of the mean,
    // would be lighter than the early wood without: E stops at 0.
    ASSERT_TRUE(removeAnatomyTone(grain, std::vector<double>{0.84, 1.0, 0.9}));
    const nlohmann::json& e = grain["colour"]["late_wood_profile"];
    EXPECT_NEAR(e[0].get<double>(), 0.5, 1e-3);
    EXPECT_NEAR(e[1].get<double>(), 0.5, 1e-3);
    EXPECT_NEAR(e[2].get<double>(), 0.0, 1e-3);
    // Early and late wood alike: nothing to move.
    nlohmann::json flat = {{"colour",
                            {{"early_wood", {0.5, 0.5, 0.5}},
                             {"late_wood", {0.5, 0.5, 0.5}},
                             {"late_wood_profile", {0.9, 0.5}}}}};
    EXPECT_FALSE(removeAnatomyTone(flat, std::vector<double>{0.8, 1.2}));
    EXPECT_DOUBLE_EQ(flat["colour"]["late_wood_profile"][0].get<double>(), 0.9);
}

}  // namespace
}  // namespace nenrin
