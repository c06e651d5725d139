#pragma once
/// Two-dimensional low-discrepancy samples: the first two dimensions of the Sobol sequence (a
/// (0,2)-sequence), with the sample order shuffled by hash-based Owen scrambling of the index
/// (Burley 2020, "Practical Hash-based Owen Scrambling") and the values digitally shifted (xor)
/// per seed. Any 2^k samples from the start are stratified in every dyadic box of area 2^-k;
/// different seeds (one per pixel and pair of dimensions) are decorrelated by the shuffle, so
/// pairs can be "padded" together. A full Owen scramble of the values as well cost 12 % of a
/// render for no visible gain.

#include <array>
#include <cstdint>
#include <utility>

#include "util/hash.h"

namespace nenrin {

namespace sobol_detail {

constexpr uint32_t reverseBits(uint32_t x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
    x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
    return (x >> 16) | (x << 16);
}

/// Laine and Karras' hash: each output bit depends on itself and the bits below it only.
constexpr uint32_t laineKarras(uint32_t x, uint32_t seed) {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

/// The second Sobol dimension (generator matrix: Pascal's triangle mod 2) of an index given
/// bit-reversed, one table per byte: entry [b][v] is the xor of the columns of the set bits of
/// byte b = v. Branch-free: a scrambled index has about 16 bits set.
inline constexpr auto kSobolSecondByByte = [] {
    std::array<uint32_t, 32> column{};
    column[0] = 1u << 31;
    for (int i = 1; i < 32; ++i) column[i] = column[i - 1] ^ (column[i - 1] >> 1);
    std::array<std::array<uint32_t, 256>, 4> table{};
    for (int b = 0; b < 4; ++b)
        for (int v = 0; v < 256; ++v)
            for (int k = 0; k < 8; ++k)
                if (v >> k & 1) table[b][v] ^= column[31 - (8 * b + k)];  // reversed bit order
    return table;
}();

inline uint32_t sobolSecondOfReversed(uint32_t reversedIndex) {
    return kSobolSecondByByte[0][reversedIndex & 0xff] ^
           kSobolSecondByByte[1][reversedIndex >> 8 & 0xff] ^
           kSobolSecondByByte[2][reversedIndex >> 16 & 0xff] ^
           kSobolSecondByByte[3][reversedIndex >> 24];
}

}  // namespace sobol_detail

/// Sample `index` of the sequence of `seed`, in [0, 1)^2.
inline std::pair<double, double> scrambledSobol2D(uint32_t index, uint64_t seed) {
    using namespace sobol_detail;
    const uint64_t h = mix64(seed);
    // The shuffled index, kept bit-reversed: that is the first Sobol dimension as a fraction,
    // and the second is the xor of the columns of its set bits.
    const uint32_t x = laineKarras(reverseBits(index), static_cast<uint32_t>(h));
    const uint32_t y = sobolSecondOfReversed(x);
    const uint64_t shift = mix64(h);
    return {(x ^ static_cast<uint32_t>(shift)) * 0x1.0p-32,
            (y ^ static_cast<uint32_t>(shift >> 32)) * 0x1.0p-32};
}

}  // namespace nenrin
