#pragma once
/// Smooth value noise in [-1, 1] on a unit lattice (trilinear between seeded lattice values,
/// smoothstep-weighted): fibre streaks, bark plates. Deterministic for a seed.

#include <cmath>
#include <cstdint>

#include "util/hash.h"

namespace nenrin {

inline double latticeValue(uint64_t seed, long long x, long long y, long long z) {
    return uniform01(hashCombine(seed, 11),
                     static_cast<uint64_t>(x) * 0x9E3779B97F4A7C15ull ^ static_cast<uint64_t>(y),
                     static_cast<uint64_t>(z));
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
        v += w * (2 * latticeValue(seed, ix + dx, iy + dy, iz + dz) - 1);
    }
    return v;
}

}  // namespace nenrin
