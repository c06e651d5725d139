#include "grain/growth_terms.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace nenrin {
namespace {

TEST(GrowthTerms, ElongationTimeIsEquation2FromNodeBirths) {
    // Constant Sa: a segment from 3 m to 4 m along the path has node births 3 / Sa and 4 / Sa,
    // and fraction t of it is reached at Da / Sa = (3 + t) / Sa.
    const double sa = 0.5;
    for (double t : {0.0, 0.25, 0.6, 1.0})
        EXPECT_NEAR(elongationTime(3 / sa, 1 / sa, t), (3 + t) / sa, 1e-14) << t;
    EXPECT_EQ(elongationTime(6, 2, 0.25), 6.5);
}

TEST(GrowthTerms, ThickeningTimeIsEquation3) {
    // Db / S with S = Sb gamma f, from the 1 / (Sb gamma) the field keeps per segment.
    EXPECT_DOUBLE_EQ(thickeningTime(0.02, 1 / 0.004, 1), 5.0);
    const double sb = 0.004, gamma = 0.7;
    for (double f : {1.0, 1.3, 0.85})
        for (double db : {0.0, 0.02, 0.137}) {
            const double paper = db / (sb * gamma * f);
            EXPECT_NEAR(thickeningTime(db, 1 / (sb * gamma), f), paper, 1e-14 * (1 + paper))
                << db << " " << f;
        }
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

/// Eq. 4 as the paper writes it for a pair: (T1 M1 + T2 M2) / (M1 + M2).
double pairBlend(double t1, double m1, double t2, double m2) {
    return (t1 * m1 + t2 * m2) / (m1 + m2);
}

double jointBlendOfPair(double t1, double m1, double t2, double m2) {
    const double times[] = {t1, t2}, distances[] = {m1, m2};
    return jointBlend(times, distances, -1);
}

TEST(GrowthTerms, JointBlendIsEquation4OverAChainsMembers) {
    EXPECT_EQ(jointBlendOfPair(10, 1, 20, 0), 10);  // on plane b: all T1
    EXPECT_EQ(jointBlendOfPair(10, 0, 20, 1), 20);  // on plane a: all T2
    EXPECT_EQ(jointBlendOfPair(10, 1, 20, 3), 17.5);
    // Two members: the pair's formula.
    for (int i = 1; i <= 50; ++i) {
        const double t1 = 3 + 0.37 * i, t2 = 40 - 0.61 * i, m1 = 0.013 * i, m2 = 0.9 / i;
        EXPECT_NEAR(jointBlendOfPair(t1, m1, t2, m2), pairBlend(t1, m1, t2, m2), 1e-13 * 40) << i;
    }
    // Three (P in both neighbours' slabs): the weighted mean, and the pair's formula where
    // an outer member's plane distance is 0.
    const double times[] = {10, 14, 20};
    const double m[] = {0.3, 0.2, 0.5}, noFirst[] = {0, 0.2, 0.5};
    EXPECT_NEAR(jointBlend(times, m, -1), (10 * 0.3 + 14 * 0.2 + 20 * 0.5) / 1.0, 1e-13);
    EXPECT_NEAR(jointBlend(times, noFirst, -1), pairBlend(14, 0.2, 20, 0.5), 1e-13);
    // No weight at all (P on every joint plane at once): the time given for that case.
    const double none[] = {0, 0, 0};
    EXPECT_EQ(jointBlend(times, none, 14.5), 14.5);
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

TEST(GrowthTerms, JunctionSumIsEquation5OverManyBranchPaths) {
    const double t1 = 10;
    // One branch path of weight 1 is junctionBlend, bit for bit.
    for (double t2 : {3.0, 6.0, 14.0})
        for (double s : {0.3, 0.8, 1.0})
            for (double p : {2.0, 5.0}) {
                const double e = t2 / s;
                JunctionSum sum(std::min(t1, e), t1, p);
                sum.add(e, 1);
                EXPECT_EQ(sum.time(), junctionBlend(t1, t2, s, p)) << t2 << " " << s << " " << p;
            }
    // Several, weighted: T = (T1^-p + sum_c w_c E_c^-p)^(-1/p) written out.
    const std::pair<double, double> paths[] = {{7, 1}, {12, 0.5}, {30, 0.2}};
    for (double p : {2.0, 3.0, 8.0}) {
        double m = t1;
        for (auto [e, w] : paths) m = std::min(m, e);
        JunctionSum sum(m, t1, p);
        double direct = std::pow(t1, -p), branches = 0;
        for (auto [e, w] : paths) {
            EXPECT_NEAR(sum.add(e, w), w * std::pow(m / e, p), 1e-15) << p;
            branches += w * std::pow(e, -p);
        }
        direct += branches;
        EXPECT_NEAR(sum.time(), std::pow(direct, -1 / p), 1e-12 * t1) << p;
        EXPECT_NEAR(sum.branchShare(), branches / direct, 1e-12) << p;
        EXPECT_NEAR(sum.sum(), direct * std::pow(m, p), 1e-12) << p;
    }
    // A path of weight 0 changes nothing.
    JunctionSum a(7, t1, 2), b(7, t1, 2);
    a.add(7, 1);
    b.add(7, 1);
    EXPECT_EQ(b.add(9, 0), 0);
    EXPECT_EQ(a.time(), b.time());
    EXPECT_EQ(a.branchShare(), b.branchShare());
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

TEST(GrowthTerms, AbruptLateWoodDarkensTowardsTheRingsEnd) {
    // A band of 0.2 of the ring from phase 0.8, stepping over 0.02; the early wood rising to
    // 0.1 at the band, the band rising from 1 - 0.4 to 1.
    LateWoodShape shape;
    shape.share = 0.2;
    shape.transition = 0.02;
    shape.earlyRise = 0.1;
    shape.lateRamp = 0.4;
    EXPECT_DOUBLE_EQ(lateWoodFraction(7.0, shape), 0);             // the ring's start
    EXPECT_NEAR(lateWoodFraction(7.4, shape), 0.1 * 0.25, 1e-12);  // (0.4 / 0.8)^2
    EXPECT_NEAR(lateWoodFraction(7.79, shape), 0.1 * (0.79 / 0.8) * (0.79 / 0.8), 1e-12);
    EXPECT_NEAR(lateWoodFraction(7.81, shape), 0.1 + 0.9 * 0.6 * 1.0 + 0.9 * 0.4 * 0.05, 1e-12);
    EXPECT_NEAR(lateWoodFraction(7.9, shape), 0.1 + 0.9 * (1 - 0.4 * 0.5), 1e-12);
    EXPECT_NEAR(lateWoodFraction(7.999999, shape), 1, 1e-5);  // darkest at the boundary
    // Monotone within the ring (the late-wood share is read where E crosses 0.5).
    double last = -1;
    for (int i = 0; i < 1000; ++i) {
        const double e = lateWoodFraction(7 + i / 1000.0, shape);
        EXPECT_GE(e, last) << i;
        last = e;
    }
    // Without the two, the plain step.
    shape.earlyRise = shape.lateRamp = 0;
    EXPECT_DOUBLE_EQ(lateWoodFraction(7.4, shape), 0);
    EXPECT_DOUBLE_EQ(lateWoodFraction(7.9, shape), 1);
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

TEST(GrowthTerms, RadialJitterIsItsThreeHarmonicsOfTheAzimuth) {
    // Section 4.5's second method written out with libm: 1 + jitter sum_k sin(k az + phase_k +
    // drift_k Ta) / k / (1 + 1/2 + 1/3), az the normal's azimuth about the axis. The field takes
    // the harmonics by angle sums from a per-segment frame, without atan2.
    SwayParams sway;
    sway.radialJitter = 0.08;
    sway.seed = 5;
    const SwayWaves waves = makeSwayWaves(sway);
    double worst = 0;
    for (int i = 0; i < 2000; ++i) {
        const double a = 0.37 * i, b = 0.011 * i * i;
        const Vec3 axis = normalize(Vec3{std::sin(a) * 0.6, std::cos(b) * 0.5, 1.0 - 0.002 * i});
        const Vec3 n = normalize(Vec3{std::cos(1.3 * i), std::sin(0.7 * i), std::sin(2.1 * i)});
        const double ta = 0.05 * i;
        const SwayFrame f = swayFrame(axis);
        EXPECT_NEAR(dot(f.u, axis), 0, 1e-15);
        EXPECT_NEAR(dot(f.v, axis), 0, 1e-15);
        const double az = std::atan2(dot(n, f.v), dot(n, f.u));
        double h = 0;
        for (int k = 0; k < SwayWaves::kWaves; ++k)
            h +=
                std::sin((k + 1) * az + waves.radialPhase[k] + waves.radialDrift[k] * ta) / (k + 1);
        const double expected = 1 + sway.radialJitter * h / (1.0 + 1.0 / 2 + 1.0 / 3);
        worst = std::max(worst, std::abs(swayRadialFactor(n, f, ta, waves) - expected));
        EXPECT_EQ(swayRadialFactor(n, axis, ta, waves), swayRadialFactor(n, f, ta, waves));
    }
    EXPECT_LT(worst, 1e-10);  // the sines to 7e-10, times jitter / (1 + 1/2 + 1/3)
    // A normal along the axis has no azimuth: atan2(0, 0) = 0's value, finite.
    const double along = swayRadialFactor({0, 0, 1}, Vec3{0, 0, 1}, 3, waves);
    double h0 = 0;
    for (int k = 0; k < SwayWaves::kWaves; ++k)
        h0 += std::sin(waves.radialPhase[k] + waves.radialDrift[k] * 3) / (k + 1);
    EXPECT_NEAR(along, 1 + sway.radialJitter * h0 / (1.0 + 1.0 / 2 + 1.0 / 3), 1e-7);
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
