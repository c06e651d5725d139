#include "skeleton/sources/kunii/kunii_growth_law.h"

#include <gtest/gtest.h>

#include <cmath>

namespace nenrin {
namespace {

TEST(KuniiGrowthLaw, ZeroAtTheCompensationPointNegativeBelowPositiveAbove) {
    KuniiGrowthLaw law;
    for (double g = 0.05; g <= 1.0; g += 0.05) {
        double Ic = compensationIrradiance(law, g);
        EXPECT_DOUBLE_EQ(Ic, law.f * g);
        EXPECT_NEAR(relativeGrowthRate(law, g, Ic), 0.0, 1e-15) << g;
        EXPECT_LT(relativeGrowthRate(law, g, Ic - 0.01), 0.0) << g;
        EXPECT_GT(relativeGrowthRate(law, g, Ic + 0.01), 0.0) << g;
        // The rate saturates at a (g + b) in full light.
        EXPECT_LT(relativeGrowthRate(law, g, 100.0), law.a * (g + law.b) + 1e-12);
        EXPECT_NEAR(relativeGrowthRate(law, g, 100.0), law.a * (g + law.b), 1e-9);
        // The slope at the compensation point is a (g + b) (c (g - d)^2 + e).
        double h = 1e-6;
        EXPECT_NEAR(
            (relativeGrowthRate(law, g, Ic + h) - relativeGrowthRate(law, g, Ic - h)) / (2 * h),
            compensationSlope(law, g), 1e-5);
    }
}

TEST(KuniiGrowthLaw, ToleranceIsBestInShadeIntoleranceInSun) {
    KuniiGrowthLaw law;
    // The paper's premise: tolerant species (small g) win in the shade, intolerant in the sun.
    EXPECT_LT(globallyBestSpecies(law, 0.15, 0.05, 1.0), 0.2);
    EXPECT_GT(globallyBestSpecies(law, 1.0, 0.05, 1.0), 0.9);
    EXPECT_GT(relativeGrowthRate(law, 0.1, 0.2), relativeGrowthRate(law, 0.9, 0.2));
    EXPECT_LT(relativeGrowthRate(law, 0.1, 0.9), relativeGrowthRate(law, 0.9, 0.9));
}

TEST(KuniiCusp, TheShiftRemovesTheCubicTermAndReproducesTheLinearisedLaw) {
    KuniiGrowthLaw law;
    for (double I = 0.0; I <= 2.0; I += 0.1) {
        CuspQuartic q = cuspQuartic(law, I);
        EXPECT_NEAR(q.cubicResidue, 0.0, 1e-12) << I;
        EXPECT_DOUBLE_EQ(q.alpha, law.a * law.c * law.f);
        EXPECT_DOUBLE_EQ(q.shift, (I + law.f * (2 * law.d - law.b)) / (4 * law.f));
        for (double g = -0.5; g <= 1.5; g += 0.125) {
            double G = g - q.shift;
            double quartic = -q.alpha * (G * G * G * G - q.p * G * G - q.q * G + q.r);
            EXPECT_NEAR(quartic, linearisedGrowthRate(law, g, I), 1e-9) << I << " " << g;
        }
    }
}

TEST(KuniiCusp, StationaryPointsSolveEquation3AndCountThreeWhereBistable) {
    KuniiGrowthLaw law;
    int bistable = 0, monostable = 0;
    for (double I = 0.0; I <= 1.5; I += 0.05) {
        std::vector<double> roots = stationarySpecies(law, I);
        ASSERT_TRUE(roots.size() == 1 || roots.size() == 3);
        EXPECT_EQ(roots.size() == 3, isBistable(law, I)) << I;
        (roots.size() == 3 ? bistable : monostable)++;
        for (double g : roots) {
            double h = 1e-6;
            double slope =
                (linearisedGrowthRate(law, g + h, I) - linearisedGrowthRate(law, g - h, I)) /
                (2 * h);
            EXPECT_NEAR(slope, 0.0, 1e-6) << I << " " << g;
        }
    }
    // The cusp: both regimes occur over this irradiance range (for the default constants
    // the fold lies between I = 0.15 and 0.3, docs/stand-kunii.md).
    EXPECT_GT(bistable, 0);
    EXPECT_GT(monostable, 0);
    EXPECT_FALSE(isBistable(law, 0.2));
    EXPECT_TRUE(isBistable(law, 0.5));
}

TEST(KuniiCusp, FollowingTheBestSpeciesShowsHysteresis) {
    KuniiGrowthLaw law;
    std::vector<double> up, down;
    for (int i = 0; i <= 18; ++i) up.push_back(0.1 + 0.05 * i);  // 0.1 .. 1.0
    down.assign(up.rbegin(), up.rend());
    std::vector<double> gUp = sweepBestSpecies(law, up, 0.05, 0.05, 1.0);
    std::vector<double> gDown = sweepBestSpecies(law, down, 1.0, 0.05, 1.0);
    // At I = 0.5 (index 8 up, 10 down) the population coming from the shade is still
    // tolerant, the one coming from the sun still intolerant.
    EXPECT_NEAR(up[8], 0.5, 1e-12);
    EXPECT_NEAR(down[10], 0.5, 1e-12);
    EXPECT_LT(gUp[8], 0.3);
    EXPECT_GT(gDown[10], 0.9);
    // Coming down, the intolerant branch disappears and the population jumps to tolerance.
    EXPECT_LT(gDown.back(), 0.2);
}

}  // namespace
}  // namespace nenrin
