#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "renderer/bake/bake_specs.h"
#include "renderer/bake/grid_bake.h"
#include "skeleton/skeleton_index.h"
#include "skeleton/synthetic_tree.h"
#include "tests/test_trees.h"

namespace nenrin {
namespace {

TEST(Bake, CrossSectionPixelsHoldTheAnalyticGrowthTime) {
    Skeleton sk = test::straightTrunk(10, 0.5);
    SkeletonIndex index(sk);
    GrainParams g;
    g.radialSpeed = 0.004;
    GrowthField field(index, g);
    WoodShader shader(field);
    SliceSpec spec;
    spec.plane = SlicePlane::Cross;
    spec.at = 2;
    spec.width = spec.height = 0.2;
    spec.resX = spec.resY = 40;
    BakedGrid grid = sliceGrid(sk, spec);
    bakeGrid(shader, grid, {1, true});
    for (int j = 0; j < 40; j += 7)
        for (int i = 0; i < 40; i += 5) {
            double x = -0.1 + (i + 0.5) * 0.005, y = 0.1 - (j + 0.5) * 0.005;
            double expected = 2 / 0.5 + std::hypot(x, y) / 0.004;
            EXPECT_NEAR(grid.at(i, j)[4], expected, 1e-4 * expected);
            EXPECT_EQ(grid.at(i, j)[3], 1.f);
        }
}

TEST(Bake, SameBytesForOneAndTwoThreads) {
    SyntheticTreeOptions o;
    o.totalSegments = 3000;
    Skeleton sk = makeSyntheticTree(o);
    SkeletonIndex index(sk);
    GrainParams g;
    g.sway.amplitude = 0.002;
    g.sway.radialJitter = 0.05;
    GrowthField field(index, g);
    WoodShader shader(field);
    VolumeSpec spec;
    spec.lower = {-0.15, -0.15, 4};
    spec.upper = {0.15, 0.15, 6};
    spec.resolution = 40;
    BakedGrid one = volumeGrid(spec), two = volumeGrid(spec);
    bakeGrid(shader, one, {1, true});
    bakeGrid(shader, two, {2, true});
    ASSERT_EQ(one.data.size(), two.data.size());
    EXPECT_EQ(std::memcmp(one.data.data(), two.data.data(), one.data.size() * sizeof(float)), 0);
    float knotMax = 0;
    for (size_t i = 0; i < one.sampleCount(); ++i) knotMax = std::max(knotMax, one.data[i * 6 + 5]);
    EXPECT_GT(knotMax, 0.5f);  // the volume is not trivially knot-free
}

TEST(Bake, VolumeLatticeIncludesBothFaces) {
    VolumeSpec spec;
    spec.lower = {0, 0, 0};
    spec.upper = {1, 0.5, 2};
    spec.resolution = 9;
    BakedGrid g = volumeGrid(spec);
    EXPECT_EQ(g.depth, 9);
    EXPECT_EQ(g.width, 5);   // round(9 * 1 / 2) = round(4.5)
    EXPECT_EQ(g.height, 2);  // round(9 * 0.5 / 2) = round(2.25)
    Vec3 last =
        g.origin + g.stepX * (g.width - 1) + g.stepY * (g.height - 1) + g.stepZ * (g.depth - 1);
    EXPECT_NEAR(length(last - spec.upper), 0, 1e-12);
}

TEST(Bake, FellingTimeMasksOutsideTheLog) {
    Skeleton sk = test::straightTrunk(10, 0.5);
    SkeletonIndex index(sk);
    GrainParams g;
    g.radialSpeed = 0.004;
    g.fellingTime = 24;  // at 2 m (Ta = 4): radius (24 - 4) * 0.004 = 8 cm
    GrowthField field(index, g);
    WoodShader shader(field);
    SliceSpec spec;
    spec.at = 2;
    spec.width = spec.height = 0.2;
    spec.resX = spec.resY = 64;
    BakedGrid grid = sliceGrid(sk, spec);
    bakeGrid(shader, grid, {0, true});
    double covered = 0;
    for (size_t i = 0; i < grid.sampleCount(); ++i) covered += grid.data[i * 6 + 3];
    double area = covered * (0.2 / 64) * (0.2 / 64);
    EXPECT_NEAR(area, std::numbers::pi * 0.08 * 0.08, 0.01 * std::numbers::pi * 0.0064 * 2);
}

}  // namespace
}  // namespace nenrin
