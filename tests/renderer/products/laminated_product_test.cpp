// Laminated layouts: which board a point of the block belongs to, and how far the nearest
// glue line is; the colour tint of each board.

#include "renderer/products/laminated_product.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <set>

#include "grain/cielab.h"
#include "renderer/products/cut_plan.h"

namespace nenrin {
namespace {

TEST(LaminatedLayout, GlulamStacksLamellaeAlongY) {
    LaminatedLayout g = glulamLayout(4, 0.04, 0.14, 2.0, 0, 0, 1);
    ASSERT_EQ(g.lamellae.size(), 4u);
    EXPECT_EQ(g.size, (Vec3{2.0, 0.16, 0.14}));
    for (int i = 0; i < 4; ++i) {
        double y = -0.08 + 0.04 * i + 0.02;
        EXPECT_EQ(g.lamellaAt({0.3, y, 0.01}), uint32_t(i));
        EXPECT_NEAR(g.glueDistance({0.3, y, 0.01}), 0.02, 1e-12);
    }
    EXPECT_NEAR(g.glueDistance({0.3, -0.04 + 0.001, 0.0}), 0.001, 1e-12);
    // The outer faces are not glued.
    EXPECT_NEAR(g.glueDistance({0.3, -0.08 + 0.001, 0.0}), 0.039, 1e-12);
}

TEST(LaminatedLayout, FingerJointsSplitLamellaeInZigZags) {
    LaminatedLayout g = glulamLayout(2, 0.04, 0.14, 4.0, 0.8, 1.2, 7);
    g.fingers = {0.015, 0.006};
    ASSERT_GT(g.lamellae.size(), 4u);  // each lamella in several pieces
    const auto& strip = g.layers[0].strips[0];
    ASSERT_GT(strip.pieceEnds.size(), 1u);
    double joint = strip.pieceEnds[0];
    // Across the width, the boundary moves by the finger length: the same x belongs to one
    // piece at a finger's tip and to the next at its root.
    std::set<uint32_t> seen;
    for (int k = 0; k < 7; ++k) seen.insert(g.lamellaAt({joint, -0.02, -0.07 + k * 0.0005}));
    EXPECT_EQ(seen.size(), 2u);
    EXPECT_LT(g.glueDistance({joint, -0.02, -0.07 + 0.0015}), 0.008);
}

TEST(LaminatedLayout, CltCrossesItsLayers) {
    LaminatedLayout c = cltLayout(3, 0.03, 0.15, 1.2, 0.9);
    ASSERT_EQ(c.layers.size(), 3u);
    EXPECT_EQ(c.layers[0].lengthAxis, 0);
    EXPECT_EQ(c.layers[1].lengthAxis, 2);
    EXPECT_EQ(c.layers[0].strips.size(), 6u);  // 0.9 / 0.15 boards across the outer layers
    EXPECT_EQ(c.layers[1].strips.size(), 8u);  // 1.2 / 0.15 across the middle one
    EXPECT_EQ(c.lamellae.size(), 20u);
    // A board of the middle layer runs along z: its lamella x axis is product z.
    const Lamella& middle = c.lamellae[c.lamellaAt({0.0, 0.0, 0.0})];
    EXPECT_EQ(middle.lengthAxis, 2);
    EXPECT_NEAR(std::abs(middle.lamellaFromProduct.inverse().x.z), 1.0, 1e-12);
}

TEST(LaminatedLayout, EdgeGluedBoardsSitSideBySide) {
    LaminatedLayout t = edgeGluedLayout(4, 0.03, 0.8, 1.6);
    ASSERT_EQ(t.lamellae.size(), 4u);
    EXPECT_EQ(t.lamellaAt({0, 0, -0.35}), 0u);
    EXPECT_EQ(t.lamellaAt({0, 0, 0.35}), 3u);
    EXPECT_NEAR(t.glueDistance({0.5, 0.0, 0.2 + 0.003}), 0.003, 1e-12);
}

}  // namespace
}  // namespace nenrin

namespace nenrin {
namespace {

// Boards of one product come from different trees: a few dE*ab apart (measured on the mean
// spruce colour), the same for the same seed, none with colour_variation 0.
TEST(BoardTint, BoardsDifferByAFewDeltaE) {
    CutPlanParams plan;
    plan.seed = 11;
    const Rgb wood = linearSrgbFromLab({80, 6, 18});
    double sum = 0;
    int pairs = 0;
    for (uint64_t i = 0; i < 24; ++i)
        for (uint64_t j = i + 1; j < 24; ++j) {
            sum += deltaE(labFromLinearSrgb(multiply(wood, boardTint(plan, i))),
                          labFromLinearSrgb(multiply(wood, boardTint(plan, j))));
            ++pairs;
        }
    const double mean = sum / pairs;
    std::printf("board tints: mean dE*ab between boards %.2f\n", mean);
    EXPECT_GT(mean, 1.5);
    EXPECT_LT(mean, 5.0);
    EXPECT_EQ(boardTint(plan, 3), boardTint(plan, 3));
    CutPlanParams other = plan;
    other.seed = 12;
    EXPECT_NE(boardTint(plan, 3), boardTint(other, 3));
    plan.colourVariation = 0;
    EXPECT_EQ(boardTint(plan, 5), (Rgb{1, 1, 1}));
}

}  // namespace
}  // namespace nenrin

#include "renderer/products/log_slice.h"
#include "skeleton/skeleton_index.h"
#include "tests/test_trees.h"

namespace nenrin {
namespace {

// A cookie's drying checks: V notches running in from the bark by about `depth` of the
// radius, one per check; none with count 0.
TEST(LogSlice, DryingChecksNotchTheOutline) {
    Skeleton trunk = test::straightTrunk(10, 0.5);
    SkeletonIndex index(trunk);
    GrainParams grain;
    grain.fellingTime = 30;
    GrowthField field(index, grain);
    auto outline = [&](int checks) {
        LogSliceParams p;
        p.checks = checks;
        p.checkDepth = 0.3;
        TriangleMesh m = logSliceMesh(field, p);
        std::vector<double> r;
        for (size_t i = 2; i < m.positions.size(); i += 2)
            r.push_back(std::hypot(m.positions[i].x, m.positions[i].z));
        return r;
    };
    std::vector<double> plain = outline(0), checked = outline(2);
    ASSERT_EQ(plain.size(), checked.size());
    int notched = 0, deepest = 0;
    double minShare = 1;
    for (size_t i = 0; i < plain.size(); ++i) {
        double share = checked[i] / plain[i];
        notched += share < 0.999;
        minShare = std::min(minShare, share);
        deepest += share < 0.9;
    }
    EXPECT_GE(notched, 2 * 3);   // each check spans a few outline vertices
    EXPECT_LE(notched, 2 * 12);  // and stays a crack
    EXPECT_LT(minShare, 1 - 0.3 * 0.6 + 0.02);
    EXPECT_GT(minShare, 1 - 0.3 * 1.4 - 0.02);
    EXPECT_GE(deepest, 2);
}

}  // namespace
}  // namespace nenrin
