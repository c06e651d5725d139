#include "skeleton/sources/kunii/kunii_fell.h"

#include <gtest/gtest.h>

#include <cmath>

#include "skeleton/segment_geometry.h"
#include "skeleton/skeleton_file.h"
#include "skeleton/skeleton_writer.h"
#include "util/input_error.h"

namespace nenrin {
namespace {

const Stand& testStand() {
    static const Stand stand = [] {
        StandOptions o;
        o.seed = 11;
        o.trees = 60;
        o.plotSize = 30;
        o.years = 80;
        return simulateStand(o);
    }();
    return stand;
}

double distanceToSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
    Vec3 ab = b - a;
    double t = std::clamp(dot(p - a, ab) / dot(ab, ab), 0.0, 1.0);
    return length(p - (a + ab * t));
}

void expectValidFelledTree(const Stand& stand, uint32_t id) {
    const StandTree& tree = stand.trees[id];
    Skeleton sk = fellStandTree(stand, id);
    ASSERT_FALSE(sk.empty());
    const SkeletonChain& trunk = sk.chain(0);
    Vec3 top = sk.end(sk.segment(trunk.segmentCount - 1));
    EXPECT_NEAR(top.z, tree.last().height, 1e-9);
    EXPECT_EQ(sk.node(0).position, (Vec3{0, 0, 0}));
    for (const SkeletonSegment& s : sk.segments()) {
        EXPECT_GE(length(sk.end(s) - sk.start(s)), 1e-6);
        EXPECT_GE(sk.node(s.to).birthTime, sk.node(s.from).birthTime);
        EXPECT_GE(sk.node(s.from).birthTime, 0.0);
        EXPECT_LE(sk.node(s.to).birthTime, tree.history.size() + 1e-9);
    }
    for (uint32_t c = 1; c < sk.chains().size(); ++c) {
        const SkeletonSegment& first = sk.segment(sk.chain(c).firstSegment);
        const SkeletonSegment& parent = sk.segment(static_cast<uint32_t>(first.parent));
        EXPECT_EQ(parent.chain, static_cast<uint32_t>(sk.chain(c).parentChain));
        EXPECT_LT(distanceToSegment(sk.start(first), sk.start(parent), sk.end(parent)), 1e-9);
        // A branch starts when its parent reached that point.
        EXPECT_NEAR(sk.node(first.from).birthTime, sk.node(parent.to).birthTime, 1e-9);
        // Dead limbs are the ones the crown base has passed; they died when it did.
        if (first.order == 1 && std::isfinite(first.deathTime)) {
            EXPECT_LE(sk.start(first).z, tree.last().crownBase + 1e-9);
            EXPECT_GE(first.deathTime, sk.node(first.from).birthTime);
        } else if (first.order == 1) {  // (sub-branches of a dead limb die with it)
            EXPECT_GT(sk.start(first).z, tree.last().crownBase);
        }
    }
    // The leader reached each trunk node's height in the year its height history passed it.
    for (uint32_t i = 0; i < trunk.segmentCount; ++i) {
        const SkeletonNode& n = sk.node(sk.segment(i).to);
        int year = static_cast<int>(std::ceil(n.birthTime));
        ASSERT_GE(year, 1);
        EXPECT_LE(n.position.z, tree.history[static_cast<size_t>(year - 1)].height + 1e-9);
        const TreeYear& before =
            year >= 2 ? tree.history[static_cast<size_t>(year - 2)] : tree.initial;
        EXPECT_GE(n.position.z, before.height - 1e-9);
    }
    // Rings: the stem radius gained each year.
    ASSERT_EQ(sk.ringWidths().size(), tree.history.size());
    double previous = 0, sum = 0;
    for (size_t k = 0; k < tree.history.size(); ++k) {
        double increment = tree.history[k].stemRadius - previous;
        EXPECT_DOUBLE_EQ(sk.ringWidths()[k], std::max(increment, 1e-5)) << k;
        previous = tree.history[k].stemRadius;
        sum += sk.ringWidths()[k];
    }
    EXPECT_NEAR(sum, tree.last().stemRadius, 1e-5 * tree.history.size());
}

TEST(KuniiFell, DominantAndSuppressedTreesMakeValidSkeletons) {
    const Stand& stand = testStand();
    expectValidFelledTree(stand, pickStandTree(stand, TreePick::Dominant));
    expectValidFelledTree(stand, pickStandTree(stand, TreePick::Suppressed));
}

TEST(KuniiFell, EveryTreeThatGrewFellsIntoAValidSkeleton) {
    // Living and dead, seedlings and canopy trees alike.
    const Stand& stand = testStand();
    int felled = 0;
    for (const StandTree& tree : stand.trees) {
        if (tree.history.empty()) {
            EXPECT_THROW(fellStandTree(stand, tree.id), InputError);
            continue;
        }
        Skeleton sk = fellStandTree(stand, tree.id);
        for (const SkeletonSegment& s : sk.segments()) {
            ASSERT_GE(length(sk.end(s) - sk.start(s)), 1e-6) << "tree " << tree.id;
            ASSERT_GE(sk.node(s.to).birthTime, sk.node(s.from).birthTime) << "tree " << tree.id;
        }
        ASSERT_EQ(sk.ringWidths().size(), tree.history.size());
        ++felled;
    }
    EXPECT_GT(felled, 100);
}

TEST(KuniiFell, ADominantTreeCarriesDeadKnotsBelowItsCrown) {
    const Stand& stand = testStand();
    Skeleton sk = fellStandTree(stand, pickStandTree(stand, TreePick::Dominant));
    int dead = 0, live = 0;
    for (const SkeletonChain& c : sk.chains())
        if (c.order == 1) (std::isfinite(sk.segment(c.firstSegment).deathTime) ? dead : live)++;
    EXPECT_GT(dead, 0);
    EXPECT_GT(live, 0);
}

TEST(KuniiFell, ADeadLimbReachesTheCrownRadiusOfTheYearItDied) {
    const Stand& stand = testStand();
    uint32_t id = pickStandTree(stand, TreePick::Dominant);
    const StandTree& tree = stand.trees[id];
    Skeleton sk = fellStandTree(stand, id);
    // Limb of every chain (the first-order chain it hangs from) and each limb's reach.
    std::vector<uint32_t> limb(sk.chains().size(), 0);
    std::vector<double> reach(sk.chains().size(), 0);
    for (uint32_t c = 1; c < sk.chains().size(); ++c) {
        const SkeletonChain& chain = sk.chain(c);
        limb[c] = chain.order == 1 ? c : limb[static_cast<size_t>(chain.parentChain)];
        Vec3 base = sk.start(sk.segment(sk.chain(limb[c]).firstSegment));
        for (uint32_t i = 0; i < chain.segmentCount; ++i) {
            Vec3 p = sk.end(sk.segment(chain.firstSegment + i));
            reach[limb[c]] = std::max(reach[limb[c]], std::hypot(p.x - base.x, p.y - base.y));
        }
    }
    int checked = 0;
    for (uint32_t c = 1; c < sk.chains().size(); ++c) {
        const SkeletonSegment& first = sk.segment(sk.chain(c).firstSegment);
        if (sk.chain(c).order != 1 || !std::isfinite(first.deathTime)) continue;
        int died = static_cast<int>(first.deathTime);
        ASSERT_GE(died, 1);
        // The crown base passed the limb that year, not before.
        EXPECT_GE(tree.history[static_cast<size_t>(died - 1)].crownBase, sk.start(first).z);
        const TreeYear& before =
            died >= 2 ? tree.history[static_cast<size_t>(died - 2)] : tree.initial;
        EXPECT_LT(before.crownBase, sk.start(first).z);
        EXPECT_NEAR(reach[c], tree.history[static_cast<size_t>(died - 1)].crownRadius, 1e-9);
        ++checked;
    }
    EXPECT_GT(checked, 3);
}

TEST(KuniiFell, FelledTreeSurvivesTheSkeletonFile) {
    const Stand& stand = testStand();
    Skeleton sk = fellStandTree(stand, pickStandTree(stand, TreePick::Suppressed));
    Skeleton back = parseSkeleton(skeletonToJson(sk, {}), "felled.json");
    EXPECT_EQ(back.segments().size(), sk.segments().size());
    EXPECT_EQ(back.ringWidths(), sk.ringWidths());
}

TEST(KuniiFell, EveryPresetFells) {
    const Stand& stand = testStand();
    uint32_t id = pickStandTree(stand, TreePick::Dominant);
    for (const std::string& name : aSystemPresetNames()) {
        FellOptions o;
        o.form = aSystemPreset(name);
        EXPECT_NO_THROW(fellStandTree(stand, id, o)) << name;
    }
}

TEST(KuniiFell, BadRequestsAreInputErrors) {
    const Stand& stand = testStand();
    EXPECT_THROW(fellStandTree(stand, static_cast<uint32_t>(stand.trees.size())), InputError);
    EXPECT_THROW(treePickFromName("tallest"), InputError);
    EXPECT_EQ(treePickFromName("suppressed"), TreePick::Suppressed);
    EXPECT_EQ(treePickNames().size(), 2u);
    FellOptions o;
    o.minRingWidth = 0;
    EXPECT_THROW(fellStandTree(stand, 0, o), InputError);
    StandOptions young;
    young.years = 5;
    young.trees = 3;
    EXPECT_THROW(pickStandTree(simulateStand(young), TreePick::Suppressed), InputError);
}

}  // namespace
}  // namespace nenrin
