#include "grain/radial_growth.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "grain/growth_field.h"
#include "tests/grain/ring_radius.h"
#include "tests/test_trees.h"

namespace nenrin {
namespace {

constexpr double kSa = 0.5, kSb = 0.004;

using test::ringRadius;

TEST(RadialGrowth, CumulativeAndInverseAgree) {
    RadialGrowth g({0.004, 0.001, 0.006}, 0.004);
    EXPECT_DOUBLE_EQ(g.cumulative(0), 0);
    EXPECT_DOUBLE_EQ(g.cumulative(1.5), 0.004 + 0.0005);
    EXPECT_DOUBLE_EQ(g.cumulative(5), 0.011 + 2 * 0.006);  // the last width continues
    EXPECT_DOUBLE_EQ(g.cumulative(-1), -0.004);            // the first width before year 0
    for (double t : {-2.0, 0.0, 0.3, 1.0, 1.7, 2.9, 3.0, 8.5})
        EXPECT_NEAR(g.inverseCumulative(g.cumulative(t)), t, 1e-12) << t;
    EXPECT_DOUBLE_EQ(g.maxSpeedRatio(), 1.5);
}

// Rings of a straight trunk with recorded widths: ring k at height z lies where the cambium,
// starting when the tip passed z, has added the widths of years z/Sa … k.
TEST(RadialGrowth, RingRadiiFollowTheRecordedYears) {
    Skeleton sk = test::straightTrunk(10, kSa);
    std::vector<double> widths;
    for (int k = 0; k < 60; ++k) widths.push_back(k >= 20 && k < 35 ? 0.001 : 0.005);
    sk.setRingWidths(widths);
    SkeletonIndex index(sk);
    GrainParams g;
    g.radialSpeed = kSb;
    GrowthField f(index, g);
    for (double z : {0.0, 2.0, 5.0})
        for (int k = 25; k <= 55; k += 5) {
            double expected = 0;
            for (int year = 0; year < k; ++year) {
                double from = std::max<double>(year, z / kSa);
                if (from < year + 1) expected += widths[year] * (year + 1 - from);
            }
            double r = ringRadius(f, {0, 0, z}, normalize(Vec3{0.6, -0.8, 0}), k);
            EXPECT_NEAR(r, expected, 1e-6) << "z " << z << " ring " << k;
        }
    // The suppressed years are narrow rings: 1 mm against 5 mm.
    Vec3 c{0, 0, 1}, d{1, 0, 0};
    EXPECT_NEAR(ringRadius(f, c, d, 31) - ringRadius(f, c, d, 30), 0.001, 1e-6);
    EXPECT_NEAR(ringRadius(f, c, d, 41) - ringRadius(f, c, d, 40), 0.005, 1e-6);
}

TEST(RadialGrowth, ConstantWidthsEqualToSbChangeNothing) {
    Skeleton plain = test::trunkWithBranch(3, normalize(Vec3{1, 0, 0.5}), 2, {0.5, 12, 1});
    Skeleton recorded = plain;
    recorded.setRingWidths(std::vector<double>(40, kSb));
    SkeletonIndex a(plain), b(recorded);
    GrainParams g;
    g.radialSpeed = kSb;
    GrowthField fa(a, g), fb(b, g);
    for (int i = 0; i < 200; ++i) {
        Vec3 p{0.002 * (i % 17) - 0.015, 0.001 * (i % 13) - 0.006, 2.5 + 0.01 * i};
        GrowthSample sa = fa.evaluate(p), sb = fb.evaluate(p);
        EXPECT_NEAR(sa.T, sb.T, 1e-9) << i;
        EXPECT_NEAR(sa.knot, sb.knot, 1e-9) << i;
    }
}

TEST(RadialGrowth, NonFiniteTimesIndexNoYear) {
    // A NaN growth time (from an overflowed input) once indexed the year table with
    // size_t(NaN); it has no year, and the answer is NaN, never a read past the table.
    RadialGrowth g({0.002, 0.004, 0.003}, 0.003);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_TRUE(std::isnan(g.cumulative(nan)));
    EXPECT_TRUE(std::isnan(g.inverseCumulative(nan)));
    EXPECT_EQ(g.cumulative(1e300), 0.009 + (1e300 - 3) * 0.003);
    EXPECT_EQ(g.cumulative(-std::numeric_limits<double>::infinity()),
              -std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace nenrin
