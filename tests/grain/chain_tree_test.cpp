#include "grain/chain_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "grain/field_segment.h"
#include "skeleton/synthetic_tree.h"
#include "util/hash.h"

namespace nenrin {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Synthetic trees from coarse to finely divided branches (1 to 80 segments per branch).
std::vector<Skeleton> testTrees() {
    std::vector<Skeleton> trees;
    for (size_t perBranch : {1u, 3u, 12u, 80u}) {
        SyntheticTreeOptions o;
        o.seed = perBranch;
        o.segmentsPerBranch = perBranch;
        o.totalSegments = 200 + 60 * perBranch;
        trees.push_back(makeSyntheticTree(o));
    }
    return trees;
}

/// A point near a random branch segment (its ends included: tips and bases are where the
/// nearest point is a chain's end), up to `spread` away.
Vec3 pointNearBranch(const Skeleton& sk, SplitMix& rng, uint32_t& chain, double spread) {
    chain = 1 + static_cast<uint32_t>(rng.uniform() * (sk.chains().size() - 1));
    const SkeletonChain& c = sk.chain(chain);
    const auto& s =
        sk.segment(c.firstSegment + static_cast<uint32_t>(rng.uniform() * c.segmentCount));
    const Vec3 on = lerp(sk.start(s), sk.end(s), rng.uniform(-0.5, 1.5));
    return on + Vec3{rng.uniform(-spread, spread), rng.uniform(-spread, spread),
                     rng.uniform(-spread, spread)};
}

TEST(ChainTrees, NearestIsThePlainLoopsAnswer) {
    // Same segment, same distance bits, with or without a limit: the bar is 0 mismatches.
    size_t queries = 0, found = 0;
    for (const Skeleton& sk : testTrees()) {
        const std::vector<FieldSegment> segments = flattenSegments(sk);
        const ChainTrees trees(segments, sk.chains());
        SplitMix rng(sk.segments().size());
        for (int q = 0; q < 5000; ++q, ++queries) {
            uint32_t chain;
            const Vec3 p = pointNearBranch(sk, rng, chain, 0.4);
            const double limit2 = q % 3 == 0 ? kInf : rng.uniform(0, 0.1);
            const ChainTrees::Nearest reference = trees.nearestByScan(chain, p, limit2);
            const ChainTrees::Nearest n = trees.nearest(chain, p, limit2);
            ASSERT_EQ(n.segment, reference.segment) << "query " << q;
            ASSERT_EQ(n.distance2, reference.distance2) << "query " << q;
            found += n.segment != kNone;
        }
    }
    EXPECT_GE(queries, 20000u);
    EXPECT_GT(found, queries / 3);  // a third of the queries have no limit
}

TEST(ChainTrees, CandidatesHoldEveryPointsNearestAndFewMore) {
    // For boxes like a bake's 8 x 8 tiles (flat ones too) near branches: every point of the
    // box has its nearest segment among the candidates; on finely divided branches the
    // candidates are the few segments the box projects onto, not the whole neighbourhood.
    size_t points = 0, candidateCount = 0, boxes = 0;
    double fineCandidates = 0, fineBoxes = 0;
    for (const Skeleton& sk : testTrees()) {
        const std::vector<FieldSegment> segments = flattenSegments(sk);
        const ChainTrees trees(segments, sk.chains()), scans(segments, sk.chains(), false);
        const bool fine = sk.chain(1).segmentCount >= 80;
        SplitMix rng(7 + sk.segments().size());
        std::vector<uint32_t> ids, scanned;
        for (int b = 0; b < 1500; ++b, ++boxes) {
            uint32_t chain;
            const Vec3 centre = pointNearBranch(sk, rng, chain, 0.3);
            Vec3 half{rng.uniform(0, 0.025), rng.uniform(0, 0.025), rng.uniform(0, 0.025)};
            if (b % 2) half.z = 0;  // a horizontal slice
            const Vec3 lo = centre - half, hi = centre + half;
            const Vec3 mid = (lo + hi) * 0.5;
            const auto nearestToCentre =
                static_cast<uint32_t>(trees.nearestByScan(chain, mid, kInf).segment);
            ids.clear();
            trees.candidates(chain, lo, hi, nearestToCentre, ids);
            scanned.clear();
            scans.candidates(chain, lo, hi, nearestToCentre, scanned);
            ASSERT_EQ(ids, scanned) << "box " << b;  // the same set, in id order
            ASSERT_TRUE(std::is_sorted(ids.begin(), ids.end()));
            candidateCount += ids.size();
            if (fine) fineCandidates += static_cast<double>(ids.size()), ++fineBoxes;
            for (int k = 0; k < 40; ++k, ++points) {
                // Corners and random points.
                const Vec3 p =
                    k < 8 ? Vec3{k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z}
                          : Vec3{rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y),
                                 rng.uniform(lo.z, hi.z)};
                const int32_t nearest = trees.nearestByScan(chain, p, kInf).segment;
                ASSERT_TRUE(
                    std::binary_search(ids.begin(), ids.end(), static_cast<uint32_t>(nearest)))
                    << "box " << b << " point " << k << ": segment " << nearest
                    << " is nearest but not a candidate";
            }
        }
    }
    EXPECT_GE(points, 200000u);
    // 80 segments of ~5 cm per branch, boxes up to 5 cm: a handful each.
    EXPECT_LT(fineCandidates / fineBoxes, 6.0) << candidateCount << " candidates";
}

TEST(ChainTrees, CandidatesHoldTheNearestJustPastJointPlanes) {
    // A point just past the plane where a segment's successor begins, far off to the side: the
    // successor is nearer than the joint by a hair (along^2, for `along` 1e-13 to 1e-7 of the
    // distance), less than the rounding of the two squared distances, so a plain loop may
    // pick either. A segment may only be ruled out when its neighbour is nearer by more than
    // rounding; else the answer would depend on the box a point came in.
    const Skeleton sk = testTrees().back();  // 80 segments per branch
    const std::vector<FieldSegment> segments = flattenSegments(sk);
    const ChainTrees trees(segments, sk.chains());
    SplitMix rng(17);
    std::vector<uint32_t> ids;
    int points = 0;
    for (uint32_t chain = 1; chain < sk.chains().size(); ++chain) {
        const SkeletonChain& c = sk.chain(chain);
        for (uint32_t s = c.firstSegment; s + 1 < c.firstSegment + c.segmentCount; ++s) {
            const FieldSegment& a = segments[s];
            const FieldSegment& b = segments[s + 1];
            // Perpendicular to the successor, towards the segment's far side of the joint.
            Vec3 side = cross(b.axis, cross(a.axis, b.axis));
            if (length(side) < 1e-9) side = cross(b.axis, Vec3{0.3, 0.5, 0.8});
            side = side * (1 / length(side));
            if (dot(side, a.axis) < 0) side = side * -1.0;
            for (int k = 0; k < 4; ++k, ++points) {
                const double r = rng.uniform(0.01, 0.5);
                const double along = r * std::pow(10.0, rng.uniform(-13, -7));
                const Vec3 p = b.a + side * r + b.axis * (k % 2 ? along : -along);
                const auto nearest = trees.nearestByScan(chain, p, kInf).segment;
                ids.clear();
                const double farthest =
                    trees.candidates(chain, p, p, static_cast<uint32_t>(nearest), ids);
                ASSERT_TRUE(
                    std::binary_search(ids.begin(), ids.end(), static_cast<uint32_t>(nearest)))
                    << "segment " << s << " point " << k << ": nearest " << nearest;
                std::vector<uint32_t> all, narrowed;
                for (uint32_t x = c.firstSegment; x < c.firstSegment + c.segmentCount; ++x)
                    all.push_back(x);
                trees.narrow(all, p, p, farthest, narrowed);
                ASSERT_TRUE(std::binary_search(narrowed.begin(), narrowed.end(),
                                               static_cast<uint32_t>(nearest)))
                    << "narrow: segment " << s << " point " << k << ": nearest " << nearest;
            }
        }
    }
    EXPECT_GT(points, 10000);
}

}  // namespace
}  // namespace nenrin
