// Akagi & Kitajima's generator (paper 2.4): pipe model, height scaling, the three branching
// forms, the skeleton's invariants, determinism and the plausibility check.
#include "skeleton/sources/akagi/akagi_generator.h"

#include <gtest/gtest.h>

#include <cmath>

#include "util/input_error.h"

namespace nenrin {
namespace {

AkagiParams monopodial() {
    AkagiParams p;
    p.mainGrowth = 0.7, p.subGrowth = 0.15, p.growthGain = 0, p.mainAngle = 3;
    return p;
}
AkagiParams sympodial() {
    AkagiParams p;
    p.mainGrowth = 0.25, p.subGrowth = 0.35, p.growthGain = 0, p.subAngle = 30;
    return p;
}
AkagiParams dichotomous() {
    AkagiParams p;
    p.mainGrowth = 0, p.subGrowth = 0.5, p.branchNum = 3, p.subAngle = 30;
    return p;
}

TEST(AkagiGenerator, RadiiObeyThePipeModel) {
    for (const AkagiParams& p : {monopodial(), sympodial(), dichotomous()}) {
        AkagiTree tree = generateAkagiTree(p, 7, 30);
        EXPECT_DOUBLE_EQ(tree.segments[0].radius, p.radius);
        for (const AkagiSegment& s : tree.segments) {
            if (s.children.empty()) continue;
            double sum = 0;
            for (int32_t c : s.children) sum += tree.segments[c].radius * tree.segments[c].radius;
            EXPECT_NEAR(sum, s.radius * s.radius, 1e-9 * s.radius * s.radius);
            // Children's areas are in the ratio of their growth elements.
            const AkagiSegment& a = tree.segments[s.children.front()];
            const AkagiSegment& b = tree.segments[s.children.back()];
            EXPECT_NEAR(a.radius * a.radius / (b.radius * b.radius),
                        a.growthElement / b.growthElement,
                        1e-9 * a.growthElement / b.growthElement);
        }
    }
}

TEST(AkagiGenerator, TopReachesHeightAndRootStartsWithGrowthElement100) {
    for (double height : {3.0, 12.5, 40.0}) {
        AkagiParams p = monopodial();
        p.height = height;
        AkagiTree tree = generateAkagiTree(p, 3, 20);
        double top = 0;
        for (const SkeletonNode& n : tree.skeleton.nodes()) top = std::max(top, n.position.z);
        EXPECT_NEAR(top, height, 1e-9 * height);
        EXPECT_NEAR(tree.stats.height, height, 1e-9 * height);
        EXPECT_EQ(tree.segments[0].growthElement, 100);
        for (const AkagiSegment& s : tree.segments) EXPECT_GE(s.growthElement, 1.0);
    }
}

struct FormMeasures {
    double mainAxisShare = 0;  // main-axis (child 0) path length / trunk chain length
    double straightness = 0;
    double branchToTrunk = 0;  // longest branch chain / trunk above the first fork
};

FormMeasures measure(const AkagiParams& p) {
    FormMeasures m;
    const int seeds = 8;
    for (int s = 0; s < seeds; ++s) {
        AkagiTree t = generateAkagiTree(p, s, 30);
        m.mainAxisShare += t.stats.mainAxisLength / t.stats.trunkLength / seeds;
        m.straightness += t.stats.trunkStraightness / seeds;
        m.branchToTrunk +=
            t.stats.longestBranchLength / (t.stats.trunkLength - t.stats.firstForkHeight) / seeds;
    }
    return m;
}

TEST(AkagiGenerator, BranchingRulesGiveTheirForms) {
    // Monopodial (P6 > P9): the main axis is the trunk, straight, much longer than any branch.
    FormMeasures mono = measure(monopodial());
    EXPECT_NEAR(mono.mainAxisShare, 1.0, 1e-9);
    EXPECT_GT(mono.straightness, 0.97);
    EXPECT_LT(mono.branchToTrunk, 0.5);
    // Sympodial (P6 <= P9): laterals take over; the main axis proper stops early and the trunk
    // chain zigzags through laterals.
    FormMeasures sym = measure(sympodial());
    EXPECT_LT(sym.mainAxisShare, 0.6);
    EXPECT_LT(sym.straightness, mono.straightness - 0.02);
    // Dichotomous (P6 = 0, P9 > 0): no main axis past the root; equal forks make branches as
    // long as the trunk chain above the first fork.
    FormMeasures dich = measure(dichotomous());
    AkagiTree t = generateAkagiTree(dichotomous(), 1, 30);
    EXPECT_NEAR(t.stats.mainAxisLength, t.stats.firstForkHeight, 1e-12);
    ASSERT_EQ(t.segments[0].children.size(), 2u);
    EXPECT_DOUBLE_EQ(t.segments[t.segments[0].children[0]].growthElement,
                     t.segments[t.segments[0].children[1]].growthElement);
    EXPECT_GT(dich.branchToTrunk, 0.85);
}

TEST(AkagiGenerator, SkeletonCarriesBirthTimesRadiiAndGamma) {
    const double years = 25;
    AkagiTree tree = generateAkagiTree(sympodial(), 11, years);
    const Skeleton& s = tree.skeleton;
    ASSERT_GT(s.chains().size(), 3u);
    EXPECT_EQ(s.chain(0).kind, SegmentKind::Trunk);
    EXPECT_EQ(s.node(0).position, Vec3(0, 0, 0));
    EXPECT_EQ(s.node(0).birthTime, 0);
    for (uint32_t c = 0; c < s.chains().size(); ++c) {
        const SkeletonChain& chain = s.chain(c);
        const SkeletonSegment& last = s.segment(chain.firstSegment + chain.segmentCount - 1);
        EXPECT_DOUBLE_EQ(s.node(last.to).birthTime, years);  // every tip grows to the end
        for (uint32_t i = 0; i < chain.segmentCount; ++i) {
            const SkeletonSegment& seg = s.segment(chain.firstSegment + i);
            EXPECT_GE(length(s.end(seg) - s.start(seg)), 1e-6);
            EXPECT_LE(s.node(seg.from).birthTime, s.node(seg.to).birthTime);
            EXPECT_GT(s.node(seg.from).radius, 0);
            EXPECT_GT(seg.gamma, 0);
            EXPECT_LE(seg.gamma, 1);
        }
        if (c == 0) continue;
        // A branch starts exactly on its parent segment's end, born when that point was.
        const SkeletonSegment& first = s.segment(chain.firstSegment);
        const SkeletonSegment& parent = s.segment(static_cast<uint32_t>(first.parent));
        EXPECT_EQ(s.start(first), s.end(parent));
        EXPECT_DOUBLE_EQ(s.node(first.from).birthTime, s.node(parent.to).birthTime);
        EXPECT_EQ(first.diebackExponent, 1);
        EXPECT_EQ(first.deathTime, kNeverDies);
    }
}

TEST(AkagiGenerator, SameSeedSameTreeOtherSeedOtherTree) {
    AkagiTree a = generateAkagiTree(monopodial(), 42, 30);
    AkagiTree b = generateAkagiTree(monopodial(), 42, 30);
    AkagiTree c = generateAkagiTree(monopodial(), 43, 30);
    ASSERT_EQ(a.skeleton.nodes().size(), b.skeleton.nodes().size());
    bool differs = false;
    for (size_t i = 0; i < a.skeleton.nodes().size(); ++i) {
        EXPECT_EQ(a.skeleton.node(i).position, b.skeleton.node(i).position);
        EXPECT_EQ(a.skeleton.node(i).birthTime, b.skeleton.node(i).birthTime);
        differs |= !(a.skeleton.node(i).position == c.skeleton.node(i).position);
    }
    EXPECT_TRUE(differs);
}

TEST(AkagiGenerator, PlausibilityCheckRejectsBadTrees) {
    std::string why;
    EXPECT_TRUE(isPlausible(generateAkagiTree(monopodial(), 1, 30), &why)) << why;
    // Laterals pointing 150 degrees away from their parent grow into the ground.
    AkagiParams drooping = monopodial();
    drooping.subAngle = 150, drooping.horizontal = 0, drooping.branchPoint = 0.05;
    EXPECT_FALSE(isPlausible(generateAkagiTree(drooping, 1, 30), &why));
    EXPECT_NE(why.find("below ground"), std::string::npos) << why;
    // A 4 m tree with a 2 m trunk radius.
    AkagiParams stump = monopodial();
    stump.height = 4, stump.radius = 2;
    EXPECT_FALSE(isPlausible(generateAkagiTree(stump, 1, 30), &why));
    EXPECT_NE(why.find("diameter"), std::string::npos) << why;
    // One child per fork and no laterals: a bare pole without a crown.
    AkagiParams pole = monopodial();
    pole.branchNum = 1;
    EXPECT_FALSE(isPlausible(generateAkagiTree(pole, 1, 30), &why));
}

TEST(AkagiGenerator, BadInputThrowsNamingTheParameter) {
    try {
        generateAkagiTree(monopodial(), 1, -3);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.where(), "years");
    }
    AkagiParams p = monopodial();
    p.mainGrowth = std::nan("");
    try {
        generateAkagiTree(p, 1, 10);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.where(), "MainGrowth");
    }
    p = monopodial();
    p.subGrowth = 1.0;  // an axis whose laterals never run out of growth element
    EXPECT_THROW(generateAkagiTree(p, 1, 10), InputError);
}

}  // namespace
}  // namespace nenrin
