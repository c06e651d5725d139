#include "grain/point_quarters.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "util/hash.h"

namespace nenrin {
namespace {

/// Splits the points and checks what the field relies on: each point lies in its quarter's
/// box, a quarter is used exactly when a point fell in it. Returns the points per quarter.
std::array<int, 4> splitAndCheck(const std::vector<Vec3>& points) {
    Vec3 lo = points[0], hi = points[0];
    for (const Vec3& p : points) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    PointQuarters q;
    q.reset(points, lo, hi);
    for (size_t i = 0; i < points.size(); ++i) EXPECT_EQ(q.quarterOf(i), 0) << "before split";
    q.split();
    std::array<int, 4> counts{};
    for (size_t i = 0; i < points.size(); ++i) {
        const int k = q.quarterOf(i);
        const Vec3& p = points[i];
        ++counts[k];
        EXPECT_TRUE(q.lo(k).x <= p.x && p.x <= q.hi(k).x && q.lo(k).y <= p.y && p.y <= q.hi(k).y &&
                    q.lo(k).z <= p.z && p.z <= q.hi(k).z)
            << "point " << i << " outside quarter " << k;
    }
    for (int k = 0; k < 4; ++k) EXPECT_EQ(q.used(k), counts[k] > 0) << k;
    return counts;
}

TEST(PointQuarters, ATileSplitsIntoFourEqualSquares) {
    std::vector<Vec3> tile;  // an 8 x 8 tile of a vertical board face (x constant)
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) tile.push_back({0.3, 0.01 * i, 1 + 0.01 * j});
    EXPECT_EQ(splitAndCheck(tile), (std::array<int, 4>{16, 16, 16, 16}));
}

TEST(PointQuarters, ALongRunSplitsAlongItsLength) {
    std::vector<Vec3> run;  // two rows of 32: a long chunk
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 32; ++i) run.push_back({0.005 * i, 0.005 * j, 2});
    EXPECT_EQ(splitAndCheck(run), (std::array<int, 4>{16, 16, 16, 16}));
}

TEST(PointQuarters, ScatteredAndDegenerateChunks) {
    SplitMix rng(9);
    for (int n : {1, 2, 5, 64}) {
        std::vector<Vec3> points;
        for (int i = 0; i < n; ++i)
            points.push_back({rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)});
        const std::array<int, 4> counts = splitAndCheck(points);
        EXPECT_EQ(counts[0] + counts[1] + counts[2] + counts[3], n);
    }
    const std::vector<Vec3> same(64, Vec3{1, 2, 3});  // all points equal: one quarter
    EXPECT_EQ(splitAndCheck(same), (std::array<int, 4>{64, 0, 0, 0}));
}

}  // namespace
}  // namespace nenrin
