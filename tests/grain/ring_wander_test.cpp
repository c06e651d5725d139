// Rings that wander (grain/ring_wander.h, util/value_noise.h): bounded by the amplitude,
// continuous, seeded, independent on the two sides of the pith, and as strong as asked.

#include "grain/ring_wander.h"

#include <gtest/gtest.h>

#include <cmath>

#include "util/hash.h"
#include "util/value_noise.h"

namespace nenrin {
namespace {

WanderParams hinokiLike() {
    WanderParams w;
    w.amplitude = 0.0025;
    w.wavelength = 0.025;
    w.along = 0.025;
    w.octaves = 3;
    w.seed = 5;
    return w;
}

/// A point of a 20 cm log, 1 m high, drawn from `i`.
Vec3 logPoint(uint64_t i) {
    return {0.2 * (uniform01(1, i) - 0.5), 0.2 * (uniform01(2, i) - 0.5), 0.5 + uniform01(3, i)};
}

TEST(RingWander, StaysWithinTheAmplitudeAndUsesIt) {
    const WanderParams w = hinokiLike();
    double sum2[3] = {0, 0, 0}, largest = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        const Vec3 d = ringWander(logPoint(i), w);
        const double c[3] = {d.x, d.y, d.z};
        for (int a = 0; a < 3; ++a) {
            sum2[a] += c[a] * c[a];
            largest = std::max(largest, std::abs(c[a]));
        }
    }
    EXPECT_LE(largest, w.amplitude);
    EXPECT_GT(largest, 0.5 * w.amplitude);
    for (double s : sum2) {
        // Smoothed value noise has an RMS of about a third of its range.
        const double rms = std::sqrt(s / n);
        EXPECT_GT(rms, 0.15 * w.amplitude);
        EXPECT_LT(rms, 0.6 * w.amplitude);
    }
}

TEST(RingWander, IsContinuousAndSeeded) {
    const WanderParams w = hinokiLike();
    // Smoothstep value noise changes by at most 3 per lattice unit along an axis; summed over
    // the octaves (weights 1, 1/2, 1/4 of 1.75, lattices 2.5 cm, 1.25 cm, 6.25 mm) that is at
    // most 0.52 m/m per axis and component: a 10 um diagonal step moves it < 1.6 x 17 um = 27 um.
    for (int i = 0; i < 1000; ++i) {
        const Vec3 p = logPoint(i);
        EXPECT_LT(length(ringWander(p + Vec3{1e-5, 1e-5, 1e-5}, w) - ringWander(p, w)), 2.7e-5);
    }
    WanderParams other = w;
    other.seed = 6;
    double differ = 0;
    for (int i = 0; i < 100; ++i)
        differ += length(ringWander(logPoint(i), w) - ringWander(logPoint(i), other));
    EXPECT_GT(differ / 100, 0.1 * w.amplitude);
    other = w;
    other.amplitude = 0;
    EXPECT_EQ(length(ringWander(logPoint(7), other)), 0.0);
}

TEST(RingWander, TheTwoSidesOfThePithWanderApart) {
    // No mirror images: the radial wander at (x, y) and at (-x, -y) are uncorrelated once the
    // two lie more than two waves apart (closer to the pith they share lattice cells).
    const WanderParams w = hinokiLike();
    double sxy = 0, sxx = 0, syy = 0;
    for (int i = 0; i < 5000; ++i) {
        const Vec3 p = logPoint(i);
        if (std::hypot(p.x, p.y) < w.wavelength) continue;
        const Vec3 r = normalize(Vec3{p.x, p.y, 0});
        const double a = dot(ringWander(p, w), r);
        const double b = dot(ringWander({-p.x, -p.y, p.z}, w), r * -1.0);
        sxy += a * b, sxx += a * a, syy += b * b;
    }
    EXPECT_LT(std::abs(sxy / std::sqrt(sxx * syy)), 0.1);
}

TEST(ValueNoise3, ComponentsAreIndependentAndInRange) {
    double sxy = 0, sxz = 0, syz = 0, sxx = 0, syy = 0, szz = 0;
    for (int i = 0; i < 20000; ++i) {
        const Vec3 v =
            valueNoise3(9, 40 * uniform01(4, i), 40 * uniform01(5, i), 40 * uniform01(6, i));
        for (double c : {v.x, v.y, v.z}) {
            ASSERT_GE(c, -1.0);
            ASSERT_LE(c, 1.0);
        }
        sxy += v.x * v.y, sxz += v.x * v.z, syz += v.y * v.z;
        sxx += v.x * v.x, syy += v.y * v.y, szz += v.z * v.z;
    }
    EXPECT_LT(std::abs(sxy / std::sqrt(sxx * syy)), 0.05);
    EXPECT_LT(std::abs(sxz / std::sqrt(sxx * szz)), 0.05);
    EXPECT_LT(std::abs(syz / std::sqrt(syy * szz)), 0.05);
    // On the lattice the noise is the corner's own value; between, it interpolates.
    const Vec3 corner = valueNoise3(9, 3, 4, 5);
    EXPECT_NEAR(valueNoise3(9, 3 + 1e-9, 4, 5).x, corner.x, 1e-6);
}

TEST(RingWander, CachedCellsGiveTheSameBitsAsEachPointAlone) {
    // A batch walks through lattice cells: runs inside one cell (the cache's case), steps into
    // the next, jumps back and far away; every octave count. The cache must never show.
    for (int octaves = 1; octaves <= 4; ++octaves) {
        WanderParams w = hinokiLike();
        w.octaves = octaves;
        RingWander cached(w);
        for (uint64_t i = 0; i < 4000; ++i) {
            const Vec3 base = logPoint(i / 16);
            const Vec3 p =
                i % 16 == 15 ? logPoint(i + 100000) : base + Vec3{1e-4, 0, 0} * double(i % 16);
            const Vec3 a = cached(p), b = ringWander(p, w);
            ASSERT_EQ(a.x, b.x) << octaves << " octaves, point " << i;
            ASSERT_EQ(a.y, b.y) << octaves << " octaves, point " << i;
            ASSERT_EQ(a.z, b.z) << octaves << " octaves, point " << i;
        }
    }
    WanderParams off = hinokiLike();
    off.amplitude = 0;
    EXPECT_EQ(length(RingWander(off)(logPoint(3))), 0.0);
}

}  // namespace
}  // namespace nenrin
