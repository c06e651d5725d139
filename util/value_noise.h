#pragma once
/// Smooth value noise in [-1, 1] on a unit lattice (trilinear between seeded lattice values,
/// smoothstep-weighted): fibre streaks, bark plates. Deterministic for a seed.

#include <cmath>
#include <cstdint>

#include "util/hash.h"

namespace nenrin {

/// A uniform [0, 1) number for lattice cell (a, b, c) of a seeded, salted pattern.
inline double cellRandom(uint64_t seed, uint64_t salt, long long a, long long b, long long c = 0) {
    return uniform01(hashCombine(seed, salt),
                     static_cast<uint64_t>(a) * 0x9E3779B97F4A7C15ull ^ static_cast<uint64_t>(b),
                     static_cast<uint64_t>(c));
}

inline double valueNoise(uint64_t seed, double x, double y, double z) {
    const double fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
    const long long ix = (long long)fx, iy = (long long)fy, iz = (long long)fz;
    auto s = [](double t) { return t * t * (3 - 2 * t); };
    const double tx = s(x - fx), ty = s(y - fy), tz = s(z - fz);
    double v = 0;
    for (int c = 0; c < 8; ++c) {
        const int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
        const double w = (dx ? tx : 1 - tx) * (dy ? ty : 1 - ty) * (dz ? tz : 1 - tz);
        v += w * (2 * cellRandom(seed, 11, ix + dx, iy + dy, iz + dz) - 1);
    }
    return v;
}

}  // namespace nenrin
