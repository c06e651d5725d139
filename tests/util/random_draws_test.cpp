#include "util/random_draws.h"

#include <gtest/gtest.h>

namespace nenrin {
namespace {

struct Moments {
    double mean = 0, variance = 0;
};

template <typename Draw>
Moments moments(Draw draw, int n) {
    double s = 0, s2 = 0;
    for (int i = 0; i < n; ++i) {
        double x = draw();
        s += x;
        s2 += x * x;
    }
    return {s / n, s2 / n - (s / n) * (s / n)};
}

TEST(RandomDraws, NormalAndGammaHaveTheirMoments) {
    constexpr int n = 200000;
    SplitMix rng(3);
    Moments normal = moments([&] { return drawNormal(rng, 2.0, 3.0); }, n);
    EXPECT_NEAR(normal.mean, 2.0, 4 * 3.0 / std::sqrt(n));
    EXPECT_NEAR(normal.variance, 9.0, 0.1);
    for (double shape : {0.5, 1.0, 4.0}) {
        Moments g = moments([&] { return drawGamma(rng, shape, 2.0); }, n);
        EXPECT_NEAR(g.mean, 2.0 * shape, 4 * 2.0 * std::sqrt(shape / n)) << shape;
        EXPECT_NEAR(g.variance / (4.0 * shape), 1.0, 0.05) << shape;
    }
}

TEST(RandomDraws, TruncatedNormalStaysInItsRange) {
    SplitMix rng(5);
    for (int i = 0; i < 10000; ++i) {
        double x = drawTruncatedNormal(rng, 173, 73, 33, 293);
        ASSERT_GE(x, 33);
        ASSERT_LE(x, 293);
    }
}

TEST(RandomDraws, SameSeedSameSequence) {
    SplitMix a(9), b(9);
    for (int i = 0; i < 100; ++i) ASSERT_EQ(drawGamma(a, 0.7, 1), drawGamma(b, 0.7, 1));
}

}  // namespace
}  // namespace nenrin
