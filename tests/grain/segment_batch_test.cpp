#include "grain/segment_batch.h"

#include <gtest/gtest.h>

#include "grain/field_segment.h"
#include "skeleton/synthetic_tree.h"
#include "util/hash.h"

namespace nenrin {
namespace {

TEST(SegmentBatch, NearestIsTheExactNearestTiesToTheFirst) {
    // The vectorised float pass (the field uses it for more than 12 kept segments of a chain)
    // must pick the smallest double distance, ties to the first, whatever the batch's origin:
    // runs of a finely divided branch, whose shared joints give exact ties beyond each joint.
    SyntheticTreeOptions o;
    o.segmentsPerBranch = 200;
    o.totalSegments = 200 + 20 * 200;
    const Skeleton sk = makeSyntheticTree(o);
    const std::vector<FieldSegment> segments = flattenSegments(sk);
    SplitMix rng(3);
    SegmentBatch batch;
    int points = 0, ties = 0;
    for (int run = 0; run < 400; ++run) {
        const SkeletonChain& chain = sk.chain(1 + static_cast<uint32_t>(rng.uniform() * 20));
        const uint32_t length = 13 + static_cast<uint32_t>(rng.uniform() * 40);
        const uint32_t first = chain.firstSegment +
                               static_cast<uint32_t>(rng.uniform() * (chain.segmentCount - length));
        const FieldSegment& middle = segments[first + length / 2];
        const Vec3 origin = middle.a + Vec3{rng.uniform(-0.05, 0.05), rng.uniform(-0.05, 0.05),
                                            rng.uniform(-0.05, 0.05)};
        batch.reset(origin);
        for (uint32_t s = first; s < first + length; ++s)
            batch.push(segments[s].a, segments[s].ab, segments[s].invLength2, s);
        for (int q = 0; q < 50; ++q, ++points) {
            // Near the run, and exactly beyond joints (where two segments tie).
            const FieldSegment& at =
                segments[first + static_cast<uint32_t>(rng.uniform() * length)];
            const double spread = q % 2 ? 0.3 : 0.002;
            const Vec3 p = at.a + Vec3{rng.uniform(-spread, spread), rng.uniform(-spread, spread),
                                       rng.uniform(-spread, spread)};
            auto exact = [&](uint32_t k) { return project(segments[batch.id(k)], p).distance2; };
            uint32_t expected = 0;
            int equal = 0;
            for (uint32_t k = 1; k < length; ++k) {
                if (exact(k) < exact(expected))
                    expected = k, equal = 0;
                else if (exact(k) == exact(expected))
                    ++equal;
            }
            ties += equal > 0;
            const SegmentBatch::Measured m = batch.measureFrom(p, 0, length);
            ASSERT_EQ(batch.nearest(0, length, m, exact), expected)
                << "run " << run << " point " << q;
        }
    }
    EXPECT_EQ(points, 20000);
    EXPECT_GT(ties, 0);  // joint ties were met
}

}  // namespace
}  // namespace nenrin
