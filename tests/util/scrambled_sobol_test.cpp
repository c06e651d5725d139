#include "util/scrambled_sobol.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

namespace nenrin {
namespace {

TEST(ScrambledSobol, EveryPowerOfTwoPrefixIsANet) {
    // The first 2^k samples of any seed put exactly one point in every dyadic box of area
    // 2^-k (all 2^a x 2^b grids with a + b = k): the (0, k, 2)-net property.
    for (uint64_t seed : {0ull, 1ull, 12345ull, 0xdeadbeefull}) {
        for (int k = 0; k <= 10; ++k) {
            const uint32_t n = 1u << k;
            std::vector<std::pair<double, double>> points;
            for (uint32_t i = 0; i < n; ++i) points.push_back(scrambledSobol2D(i, seed));
            for (int a = 0; a <= k; ++a) {
                const int b = k - a;
                std::vector<int> count(n, 0);
                for (auto [x, y] : points) {
                    ASSERT_GE(x, 0.0);
                    ASSERT_LT(x, 1.0);
                    ASSERT_GE(y, 0.0);
                    ASSERT_LT(y, 1.0);
                    const uint32_t cx = static_cast<uint32_t>(x * (1u << a));
                    const uint32_t cy = static_cast<uint32_t>(y * (1u << b));
                    ++count[(cy << a) | cx];
                }
                for (uint32_t c = 0; c < n; ++c)
                    ASSERT_EQ(count[c], 1) << "seed " << seed << ", " << n << " points, "
                                           << (1 << a) << " x " << (1 << b) << " grid, box " << c;
            }
        }
    }
}

TEST(ScrambledSobol, SeedsGiveDifferentPoints) {
    // Decorrelated pairs: the same sample index lands elsewhere under another seed.
    std::set<std::pair<double, double>> first;
    for (uint64_t seed = 0; seed < 1000; ++seed) first.insert(scrambledSobol2D(0, seed));
    EXPECT_EQ(first.size(), 1000u);
    // And the mean over many seeds of any one sample is uniform (within 3 sigma).
    for (uint32_t index : {0u, 1u, 7u, 100u}) {
        double sx = 0, sy = 0;
        const int seeds = 20000;
        for (int seed = 0; seed < seeds; ++seed) {
            auto [x, y] = scrambledSobol2D(index, static_cast<uint64_t>(seed) * 7919);
            sx += x;
            sy += y;
        }
        const double sigma = std::sqrt(1.0 / 12 / seeds);
        EXPECT_NEAR(sx / seeds, 0.5, 3 * sigma) << "index " << index;
        EXPECT_NEAR(sy / seeds, 0.5, 3 * sigma) << "index " << index;
    }
}

}  // namespace
}  // namespace nenrin
