/// The field prunes branch chains, segments and (point, chain) pairs by bounds before paying
/// for path times. Every such test must be exact: the answer is that of eq. 5 summed over
/// every branch chain of the tree, each through its nearest segment. The reference below does
/// just that, with no pruning at all, from the field's own public path time.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "grain/field_segment.h"
#include "grain/growth_field.h"
#include "skeleton/skeleton_file.h"
#include "skeleton/synthetic_tree.h"

namespace nenrin {
namespace {

/// T at p from the trunk time t1 and every branch chain, in chain order as the field sums.
double unprunedT(const GrowthField& field, const Skeleton& sk,
                 const std::vector<FieldSegment>& segments, const Vec3& p, double t1) {
    const JunctionParams& junction = field.params().junction;
    struct Term {
        double effective, weight;
    };
    std::vector<Term> terms;
    for (const SkeletonChain& chain : sk.chains()) {
        if (chain.kind != SegmentKind::Branch || chain.segmentCount == 0) continue;
        const FieldSegment& first = segments[chain.firstSegment];
        const Vec3 v = p - first.a;
        const double lv = length(v);
        const double sinAlpha = lv > 0 ? dot(v, first.axis) / lv : 0;
        if (sinAlpha <= 0) continue;
        uint32_t nearest = chain.firstSegment;
        double best = std::numeric_limits<double>::infinity();
        for (uint32_t s = chain.firstSegment; s < chain.firstSegment + chain.segmentCount; ++s) {
            const double d2 = project(segments[s], p).distance2;
            if (d2 < best) best = d2, nearest = s;
        }
        const double time = field.chainPathTime(nearest, p).T;
        const double weight = junctionReachWeight(time / sinAlpha, t1, junction.reach);
        if (weight > 0) terms.push_back({time / sinAlpha, weight});
    }
    if (terms.empty()) return t1;
    double m = t1;
    for (const Term& t : terms) m = std::min(m, t.effective);
    if (m <= 0) return 0;
    double sum = junctionTerm(m, t1, junction.p);
    for (const Term& t : terms) sum += t.weight * junctionTerm(m, t.effective, junction.p);
    return junctionCombine(m, sum, junction.p);
}

/// Sections through the tree as a bake lays them out (8 x 8 tiles of a 32 x 32 square), and
/// the count of points where a branch and a dead one had a share.
void expectUnpruned(const Skeleton& sk, const std::vector<double>& heights, double half,
                    int& knotted, int& dead) {
    SkeletonIndex index(sk);
    GrainParams params;
    params.radialSpeed = 0.004;
    GrowthField field(index, params);
    const std::vector<FieldSegment> segments = flattenSegments(sk);
    GrowthScratch scratch;
    for (const double z : heights) {
        std::vector<Vec3> points;
        const double step = 2 * half / 31;
        for (int tj = 0; tj < 32; tj += 8)
            for (int ti = 0; ti < 32; ti += 8)
                for (int j = tj; j < tj + 8; ++j)
                    for (int i = ti; i < ti + 8; ++i)
                        points.push_back({-half + step * i, -half + step * j, z});
        std::vector<GrowthSample> samples(points.size());
        field.evaluateBatch(points, samples, scratch);
        for (size_t i = 0; i < points.size(); ++i) {
            const double expected = unprunedT(field, sk, segments, points[i], samples[i].trunkTime);
            ASSERT_EQ(samples[i].T, expected) << "z " << z << " point " << i;
            knotted += samples[i].knot > 0;
            dead += samples[i].deadKnot > 0.5;
        }
    }
}

TEST(GrowthFieldPruning, SyntheticTreeWithDeadBranchesMatchesEveryChainSummed) {
    // 30 % of the branches die (dieback exponents 1 to 3): their chains are ruled out by the
    // dieback-aware bounds far sooner than living ones.
    for (const size_t perBranch : {25, 400}) {
        SyntheticTreeOptions o;
        o.segmentsPerBranch = perBranch;
        o.totalSegments = 200 + 240 * perBranch;
        int knotted = 0, dead = 0;
        expectUnpruned(makeSyntheticTree(o), {3.0, 7.5, 12.0}, 0.15, knotted, dead);
        EXPECT_GT(knotted, 50) << perBranch;  // the sections do cross branches,
        EXPECT_GT(dead, 5) << perBranch;      // dead ones among them
    }
}

TEST(GrowthFieldPruning, BundledConiferMatchesEveryChainSummed) {
    const Skeleton sk =
        loadSkeletonFile(std::string(NENRIN_SOURCE_DIR) + "/scenes/skeletons/conifer.json");
    int knotted = 0, dead = 0;
    expectUnpruned(sk, {0.64, 1.16, 2.32}, 0.12, knotted, dead);  // just above three whorls
    EXPECT_GT(knotted, 20);
    EXPECT_GT(dead, 5);
}

}  // namespace
}  // namespace nenrin
