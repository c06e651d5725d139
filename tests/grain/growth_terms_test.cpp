#include "grain/growth_terms.h"

#include <gtest/gtest.h>

#include <numbers>

namespace nenrin {
namespace {

TEST(GrowthTerms, ElongationAndThickeningTimes) {
    EXPECT_DOUBLE_EQ(elongationTime(3.0, 0.5), 6.0);     // eq. 2
    EXPECT_DOUBLE_EQ(thickeningTime(0.02, 0.004), 5.0);  // eq. 3
}

TEST(GrowthTerms, DirectionFactorFavoursTheSunSide) {
    Vec3 ray{0, 1, 0};  // light travels +Y: the sun stands at -Y
    EXPECT_DOUBLE_EQ(directionFactor({0, -1, 0}, ray, 0.2), 1.2);
    EXPECT_DOUBLE_EQ(directionFactor({0, 1, 0}, ray, 0.2), 0.8);
    EXPECT_DOUBLE_EQ(directionFactor({1, 0, 0}, ray, 0.2), 1.0);
}

TEST(GrowthTerms, AgeWarpTaperDieback) {
    EXPECT_DOUBLE_EQ(ageWarp(4.0, 1.0), 4.0);
    EXPECT_DOUBLE_EQ(ageWarp(4.0, 1.5), 8.0);           // eq. 8
    EXPECT_DOUBLE_EQ(taperFactor(0.0, 0.5, 0.9), 1.5);  // eq. 9 at the base
    EXPECT_NEAR(taperFactor(10.0, 0.5, 0.9), 1 + 0.5 * std::pow(0.9, 10), 1e-15);
    EXPECT_DOUBLE_EQ(dieback(5.0, 8.0, 2.0), 5.0);          // eq. 10: alive
    EXPECT_DOUBLE_EQ(dieback(16.0, 8.0, 2.0), 16.0 * 4.0);  // dead: T (T/Tlim)^eps
}

TEST(GrowthTerms, JointBlendWeightsByPlaneDistances) {
    EXPECT_DOUBLE_EQ(jointBlend(10, 1, 20, 0), 10);  // on plane b: all E1
    EXPECT_DOUBLE_EQ(jointBlend(10, 0, 20, 1), 20);  // on plane a: all E2
    EXPECT_DOUBLE_EQ(jointBlend(10, 1, 20, 3), 17.5);
}

TEST(GrowthTerms, JunctionBlendIsTheReconstructedEquation5) {
    // Behind plane F and in it: pure trunk time.
    EXPECT_DOUBLE_EQ(junctionBlend(10, 3, -0.2, 2), 10);
    EXPECT_DOUBLE_EQ(junctionBlend(10, 3, 0, 2), 10);
    // p = 2: T1 T2 / sqrt(T2^2 + (T1 sin a)^2).
    double t1 = 10, t2 = 6, s = 0.8;
    EXPECT_NEAR(junctionBlend(t1, t2, s, 2), t1 * t2 / std::sqrt(t2 * t2 + t1 * t1 * s * s), 1e-12);
    // Large p approaches the first-arrival minimum min(T1, T2 / sin a).
    EXPECT_NEAR(junctionBlend(t1, t2, s, 64), std::min(t1, t2 / s), 0.1);
    // Never above either path.
    EXPECT_LE(junctionBlend(t1, t2, s, 2), std::min(t1, t2 / s));
}

TEST(GrowthTerms, ReachWeightFadesToZero) {
    EXPECT_DOUBLE_EQ(junctionReachWeight(10, 10, 4), 1);
    EXPECT_DOUBLE_EQ(junctionReachWeight(20, 10, 4), 1);
    EXPECT_DOUBLE_EQ(junctionReachWeight(40, 10, 4), 0);
    EXPECT_NEAR(junctionReachWeight(30, 10, 4), 0.5, 1e-12);
}

TEST(GrowthTerms, LateWoodFractionFollowsEquation6) {
    EXPECT_DOUBLE_EQ(lateWoodFraction(3.0, 4), 0);  // ring boundary: start of early wood
    EXPECT_NEAR(lateWoodFraction(3.5, 1), std::sin(std::numbers::pi / 4), 1e-12);
    EXPECT_NEAR(lateWoodFraction(3.999999, 4), 1, 1e-6);
    EXPECT_LT(lateWoodFraction(3.5, 8), lateWoodFraction(3.5, 2));  // n narrows late wood
}

TEST(GrowthTerms, HeartwoodWeight) {
    EXPECT_DOUBLE_EQ(heartwoodWeight(5, 10, 20), 1);
    EXPECT_DOUBLE_EQ(heartwoodWeight(15, 10, 20), 0.5);
    EXPECT_DOUBLE_EQ(heartwoodWeight(25, 10, 20), 0);
}

TEST(GrowthTerms, SwayIsBoundedSeededAndSmooth) {
    SwayParams sway;
    sway.amplitude = 0.01;
    sway.radialJitter = 0.1;
    Vec3 p{0.1, 0.2, 3};
    SwayWaves waves = makeSwayWaves(sway);
    Vec3 d = swayDisplacement(p, waves);
    EXPECT_LE(std::abs(d.x), 0.01);
    EXPECT_LE(std::abs(d.z), 0.01);
    EXPECT_GT(length(d), 0);
    EXPECT_EQ(d, swayDisplacement(p, makeSwayWaves(sway)));  // deterministic
    Vec3 e = swayDisplacement(p + Vec3{1e-6, 0, 0}, waves);
    EXPECT_LT(length(e - d), 1e-6);  // smooth
    sway.seed = 2;
    EXPECT_NE(d, swayDisplacement(p, makeSwayWaves(sway)));  // seeded
    double f = swayRadialFactor({1, 0, 0}, {0, 0, 1}, 5, waves);
    EXPECT_GE(f, 0.9);
    EXPECT_LE(f, 1.1);
    SwayWaves none = makeSwayWaves(SwayParams{});
    EXPECT_EQ(swayDisplacement(p, none), Vec3{});
    EXPECT_EQ(swayRadialFactor({1, 0, 0}, {0, 0, 1}, 5, none), 1.0);
}

TEST(GrowthTerms, MicroStructureTilesEvery16CellsAndIgnoresHeight) {
    double cell = 0.001;
    Vec3 p{0.00312, -0.0071, 1.0};
    double v = microStructure(p, cell, 7);
    EXPECT_GE(v, -1);
    EXPECT_LE(v, 1);
    EXPECT_EQ(v, microStructure(p + Vec3{16 * cell, 0, 0}, cell, 7));
    EXPECT_EQ(v, microStructure(p + Vec3{0, -32 * cell, 0}, cell, 7));
    EXPECT_EQ(v, microStructure(p + Vec3{0, 0, 0.37}, cell, 7));  // projected along the trunk
    int differing = 0;
    for (int i = 1; i < 16; ++i)
        differing += microStructure(p + Vec3{i * cell, 0, 0}, cell, 7) != v;
    EXPECT_GT(differing, 10);
}

}  // namespace
}  // namespace nenrin

namespace nenrin {
namespace {

TEST(GrowthTerms, SwayWavesFollowTheirSineSum) {
    // The sway uses its own polynomial sine: it must match the documented sum of sines.
    SwayParams sway;
    sway.amplitude = 0.01;
    sway.wavelength = 0.37;
    SwayWaves w = makeSwayWaves(sway);
    constexpr double norm = 1.0 + 1.0 / 2 + 1.0 / 3;
    for (int k = 0; k < 2000; ++k) {
        Vec3 p{std::sin(k * 1.3) * 3, std::cos(k * 0.7) * 3, k * 0.01};
        Vec3 d = swayDisplacement(p, w);
        for (int axis = 0; axis < 3; ++axis) {
            double sum = 0;
            for (int i = 0; i < SwayWaves::kWaves; ++i)
                sum += std::sin(dot(w.direction[axis][i], p) + w.phase[axis][i]) / (i + 1);
            EXPECT_NEAR(d[axis], sum / norm * sway.amplitude, 1e-9);
        }
    }
}

}  // namespace
}  // namespace nenrin
