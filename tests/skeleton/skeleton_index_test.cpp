#include "skeleton/skeleton_index.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "skeleton/synthetic_tree.h"
#include "util/hash.h"

namespace nenrin {
namespace {

/// Embree and brute force must give the same answers: the bar is 0 mismatches.
TEST(SkeletonIndex, EmbreeAgreesWithBruteForceOnRandomSkeletons) {
    size_t queries = 0;
    for (uint64_t seed : {1u, 2u, 3u}) {
        SyntheticTreeOptions o;
        o.seed = seed;
        o.totalSegments = 3000 * seed;
        Skeleton sk = makeSyntheticTree(o);
        SkeletonIndex embree(sk, IndexBackend::Embree);
        SkeletonIndex brute(sk, IndexBackend::BruteForce);
        SplitMix rng(seed * 77);
        std::vector<uint32_t> a, b;
        for (int q = 0; q < 4000; ++q, ++queries) {
            Vec3 p{rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-1, 21)};
            NearestSegment ne = embree.trunk().nearest(p), nb = brute.trunk().nearest(p);
            ASSERT_EQ(ne.segment, nb.segment) << "trunk nearest, query " << q;
            ASSERT_EQ(ne.distance2, nb.distance2);
            ne = embree.branches().nearest(p);
            nb = brute.branches().nearest(p);
            ASSERT_EQ(ne.segment, nb.segment) << "branch nearest, query " << q;
            double r = rng.uniform(0.01, 0.5);
            a.clear();
            b.clear();
            embree.branches().gather(p, r, a);
            brute.branches().gather(p, r, b);
            std::sort(a.begin(), a.end());
            std::sort(b.begin(), b.end());
            ASSERT_EQ(a, b) << "gather, query " << q;
            // Chains: the same from both, and every chain with a segment within r among them.
            std::vector<uint32_t> ce, cb;
            embree.branchChains().gather(p, r, ce);
            brute.branchChains().gather(p, r, cb);
            std::sort(ce.begin(), ce.end());
            std::sort(cb.begin(), cb.end());
            ASSERT_EQ(ce, cb) << "chain gather, query " << q;
            for (uint32_t segment : b)
                ASSERT_TRUE(std::binary_search(ce.begin(), ce.end(), sk.segment(segment).chain))
                    << "chain of segment " << segment << " missing, query " << q;
            // A capped nearest finds nothing beyond its radius.
            NearestSegment capped = embree.branches().nearest(p, 0.05);
            NearestSegment cappedRef = brute.branches().nearest(p, 0.05);
            ASSERT_EQ(capped.segment, cappedRef.segment);
        }
    }
    EXPECT_GE(queries, 10000u);
}

TEST(SkeletonIndex, ClassesAreSeparate) {
    SyntheticTreeOptions o;
    o.totalSegments = 500;
    Skeleton sk = makeSyntheticTree(o);
    SkeletonIndex index(sk);
    EXPECT_EQ(index.trunk().size(), sk.trunkSegmentCount());
    EXPECT_EQ(index.branches().size(), sk.branchSegmentCount());
    NearestSegment n = index.trunk().nearest({0.5, 0.5, 5});
    ASSERT_NE(n.segment, kNone);
    EXPECT_EQ(sk.segment(n.segment).kind, SegmentKind::Trunk);
}

}  // namespace
}  // namespace nenrin
