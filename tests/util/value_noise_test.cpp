// util/value_noise: valueNoise, which shares the hashing of a cell's eight corners, is the
// smooth lattice of its corner values bit for bit (anatomy, bark and saw marks must not change
// when the hashing is reorganised), and stays in [-1, 1].

#include "util/value_noise.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>

#include "util/hash.h"

namespace nenrin {
namespace {

TEST(ValueNoise, IsTheSmoothLatticeOfItsCornerValuesBitForBit) {
    for (uint64_t seed : {0ull, 7ull, 0xba4cull, 977ull * 3 + 57}) {
        for (uint64_t i = 0; i < 20000; ++i) {
            // Points round the origin (negative cells), on lattice planes, and far out.
            const double scale = i % 3 == 0 ? 4.0 : i % 3 == 1 ? 1e6 : 0.5;
            const double x = (2 * uniform01(seed, i, 0) - 1) * scale;
            const double y = i % 7 == 0 ? 3.0 : (2 * uniform01(seed, i, 1) - 1) * scale;
            const double z = (2 * uniform01(seed, i, 2) - 1) * scale;
            const double shared = valueNoise(seed, x, y, z);
            const double each =
                smoothLattice<double>(x, y, z, [seed](long long a, long long b, long long c) {
                    return valueNoiseCorner(seed, a, b, c);
                });
            ASSERT_EQ(std::bit_cast<uint64_t>(shared), std::bit_cast<uint64_t>(each))
                << seed << " " << x << " " << y << " " << z;
            ASSERT_LE(std::abs(shared), 1.0);
        }
    }
}

}  // namespace
}  // namespace nenrin
