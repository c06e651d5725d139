#include "renderer/stats/ndimage_filters.h"

#include <gtest/gtest.h>

#include <cmath>

namespace nenrin {
namespace {

// scipy's 'reflect' mode: d c b a | a b c d | d c b a, periodic beyond one reflection.
TEST(NdimageFilters, ReflectModeRepeatsTheEdgeSample) {
    EXPECT_EQ(reflectIndex(-1, 4), 0);
    EXPECT_EQ(reflectIndex(-4, 4), 3);
    EXPECT_EQ(reflectIndex(4, 4), 3);
    EXPECT_EQ(reflectIndex(7, 4), 0);
    EXPECT_EQ(reflectIndex(8, 4), 0);
    EXPECT_EQ(reflectIndex(-9, 4), 0);
    for (int i = -5; i <= 5; ++i) EXPECT_EQ(reflectIndex(i, 1), 0);
}

// The kernel is normalised (a constant stays constant) and truncated at int(4 sigma + 0.5).
TEST(NdimageFilters, GaussianOfAnImpulseIsTheNormalisedTruncatedKernel) {
    Plane impulse(101, 1);
    impulse.at(50, 0) = 1;
    const Plane g = gaussianFilter(impulse, 4);
    double sum = 0;
    for (double v : g.values) sum += v;
    EXPECT_NEAR(sum, 1, 1e-12);
    EXPECT_GT(g.at(50 + 16, 0), 0);  // radius int(16.5) = 16
    EXPECT_EQ(g.at(50 + 17, 0), 0);
    EXPECT_NEAR(g.at(52, 0) / g.at(50, 0), std::exp(-0.5 * 4 / 16), 1e-12);

    Plane constant(40, 30, 7.5);
    for (double v : gaussianFilter(constant, 16).values) EXPECT_NEAR(v, 7.5, 1e-12);
}

// At an edge the missing neighbour is the edge sample itself.
TEST(NdimageFilters, GaussianReflectsAtTheEdge) {
    Plane step(3, 1);
    step.at(0, 0) = 1;                          // 1 0 0, read as 0 1 | 1 0 0 | 0 0
    const Plane g = gaussianFilter(step, 0.4);  // radius 2
    const double w0 = 1, w1 = std::exp(-0.5 / 0.16), w2 = std::exp(-0.5 * 4 / 0.16);
    const double norm = w0 + 2 * w1 + 2 * w2;
    EXPECT_NEAR(g.at(0, 0), (w0 + w1) / norm, 1e-12);  // the reflected 1 at -1
    EXPECT_NEAR(g.at(1, 0), (w1 + w2) / norm, 1e-12);
    EXPECT_NEAR(g.at(2, 0), w2 / norm, 1e-12);
}

// sobel(axis 1) = [-1 0 1] along x, [1 2 1] along y: a ramp in x gives 8 inside, 4 at an edge.
TEST(NdimageFilters, SobelAxisOneIsTheXDerivative) {
    Plane ramp(6, 5);
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 6; ++x) ramp.at(x, y) = x;
    const Plane gx = sobel(ramp, 1), gy = sobel(ramp, 0);
    for (int y = 0; y < 5; ++y) {
        EXPECT_DOUBLE_EQ(gx.at(0, y), 4);
        for (int x = 1; x < 5; ++x) EXPECT_DOUBLE_EQ(gx.at(x, y), 8);
        EXPECT_DOUBLE_EQ(gx.at(5, y), 4);
        for (int x = 0; x < 6; ++x) EXPECT_DOUBLE_EQ(gy.at(x, y), 0);
    }
}

TEST(NdimageFilters, MedianOfAnEvenCountAveragesTheMiddleTwo) {
    EXPECT_DOUBLE_EQ(median({4, 1, 3, 2}), 2.5);
    EXPECT_DOUBLE_EQ(median({5, 1, 3}), 3);
    EXPECT_DOUBLE_EQ(median({2}), 2);
}

}  // namespace
}  // namespace nenrin
