#include "grain/segment_lanes.h"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "grain/field_segment.h"
#include "skeleton/synthetic_tree.h"
#include "util/hash.h"

namespace nenrin {
namespace {

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// A finely divided branch: consecutive segments share joints, so points beyond a joint are
/// exactly as far from both (a tie the scan settles by order).
std::vector<FieldSegment> branchSegments() {
    SyntheticTreeOptions o;
    o.segmentsPerBranch = 60;
    o.totalSegments = 200 + 10 * 60;
    return flattenSegments(makeSyntheticTree(o));
}

TEST(SegmentLanes, NearestOfSegmentsIsTheScalarScanBitForBit) {
    // Every run length 1..64 (the vector loop pads to four lanes), points near a run of
    // segments and exactly on its joints: the lane answer must be the one a scan with
    // project() and `<` gives (index, tRaw, t, distance), bit for bit.
    const std::vector<FieldSegment> segments = branchSegments();
    SplitMix rng(5);
    PointLanes lanes;
    NearestLanes nearest;
    int ties = 0;
    for (size_t n = 1; n <= kLanes; ++n) {
        const uint32_t first = 200 + static_cast<uint32_t>(rng.uniform() * 500);
        std::vector<uint32_t> ids;
        for (uint32_t s = first; s < first + 1 + static_cast<uint32_t>(n % 9); ++s)
            ids.push_back(s);
        std::vector<Vec3> points;
        for (size_t i = 0; i < n; ++i) {
            const FieldSegment& at = segments[ids[i % ids.size()]];
            const double spread = i % 3 ? 0.02 : 0.0;  // every third point on a joint
            points.push_back(at.a + Vec3{rng.uniform(-spread, spread), rng.uniform(-spread, spread),
                                         rng.uniform(-spread, spread)});
        }
        lanes.fill(points);
        nearestOfSegments(segments, ids, lanes, n, nearest);
        for (size_t i = 0; i < n; ++i) {
            size_t best = 0;
            SegmentProjection bestProjection = project(segments[ids[0]], points[i]);
            for (size_t k = 1; k < ids.size(); ++k) {
                const SegmentProjection x = project(segments[ids[k]], points[i]);
                if (x.distance2 == bestProjection.distance2) ++ties;
                if (x.distance2 < bestProjection.distance2) best = k, bestProjection = x;
            }
            ASSERT_EQ(nearest.which[i], double(best)) << "n " << n << " point " << i;
            EXPECT_TRUE(sameBits(nearest.distance2[i], bestProjection.distance2));
            EXPECT_TRUE(sameBits(nearest.tRaw[i], bestProjection.tRaw));
            EXPECT_TRUE(sameBits(nearest.t[i], bestProjection.t));
        }
    }
    EXPECT_GT(ties, 20);  // the joints did make ties
}

TEST(SegmentLanes, MeasureInsideSegmentIsProjectBitForBit) {
    // The trunk pass's plain chunks: axis point, Ta and distance as segmentPathTime computes
    // them from project()'s tRaw.
    const std::vector<FieldSegment> segments = branchSegments();
    SplitMix rng(7);
    SegmentLanes lanes;
    for (size_t n = 1; n <= kLanes; n += 7) {
        const FieldSegment& s = segments[static_cast<size_t>(rng.uniform() * 200)];
        std::vector<Vec3> points;
        for (size_t i = 0; i < n; ++i)
            points.push_back(
                s.a + s.ab * rng.uniform() +
                Vec3{rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2)});
        measureInsideSegment(s, points, lanes);
        for (size_t i = 0; i < n; ++i) {
            const double t = project(s, points[i]).tRaw;
            const Vec3 axisPoint = s.a + s.ab * t;
            EXPECT_TRUE(sameBits(lanes.t[i], t));
            EXPECT_TRUE(sameBits(lanes.ax[i], axisPoint.x));
            EXPECT_TRUE(sameBits(lanes.ay[i], axisPoint.y));
            EXPECT_TRUE(sameBits(lanes.az[i], axisPoint.z));
            EXPECT_TRUE(sameBits(lanes.Ta[i], s.birthA + s.birthDelta * t));
            EXPECT_TRUE(sameBits(lanes.distance[i], length(points[i] - axisPoint)));
        }
    }
}

}  // namespace
}  // namespace nenrin
