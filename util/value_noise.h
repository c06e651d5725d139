#pragma once
/// Smooth value noise in [-1, 1] on a unit lattice (trilinear between seeded lattice values,
/// smoothstep-weighted): fibre streaks, bark plates. Deterministic for a seed.

#include <cmath>
#include <cstdint>

#include "util/hash.h"
#include "util/vec3.h"

namespace nenrin {

/// A uniform [0, 1) number for lattice cell (a, b, c) of a seeded, salted pattern.
inline double cellRandom(uint64_t seed, uint64_t salt, long long a, long long b, long long c = 0) {
    return uniform01(hashCombine(seed, salt),
                     static_cast<uint64_t>(a) * 0x9E3779B97F4A7C15ull ^ static_cast<uint64_t>(b),
                     static_cast<uint64_t>(c));
}

/// Trilinear, smoothstep-weighted interpolation between the values `corner(a, b, c)` gives at
/// the eight lattice points around (x, y, z); T is double or Vec3.
template <class T, class Corner>
inline T smoothLattice(double x, double y, double z, Corner corner) {
    const double fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
    const long long ix = (long long)fx, iy = (long long)fy, iz = (long long)fz;
    auto s = [](double t) { return t * t * (3 - 2 * t); };
    const double tx = s(x - fx), ty = s(y - fy), tz = s(z - fz);
    T v{};
    for (int c = 0; c < 8; ++c) {
        const int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
        const double w = (dx ? tx : 1 - tx) * (dy ? ty : 1 - ty) * (dz ? tz : 1 - tz);
        v = v + corner(ix + dx, iy + dy, iz + dz) * w;
    }
    return v;
}

inline double valueNoise(uint64_t seed, double x, double y, double z) {
    return smoothLattice<double>(x, y, z, [seed](long long a, long long b, long long c) {
        return 2 * cellRandom(seed, 11, a, b, c) - 1;
    });
}

/// Three independent value noises at once, each in [-1, 1]: one hash per lattice corner gives
/// all three (21 bits each), a third of the hashing of three valueNoise calls. For smooth
/// displacements (ring wander) evaluated many times per sample.
inline Vec3 valueNoise3(uint64_t seed, double x, double y, double z) {
    const uint64_t base = hashCombine(seed, 13);
    return smoothLattice<Vec3>(x, y, z, [base](long long a, long long b, long long c) {
        constexpr double kUnit = 0x1.0p-21;
        constexpr uint64_t kMask = (uint64_t(1) << 21) - 1;
        // Each coordinate hashed in turn: a key such as (a G) ^ b (cellRandom's) gives (a, b)
        // and (-a, -b) the same value a third of the time, and rings would mirror across the
        // pith.
        const uint64_t h = hashCombine(
            hashCombine(hashCombine(base, static_cast<uint64_t>(a)), static_cast<uint64_t>(b)),
            static_cast<uint64_t>(c));
        return Vec3{2 * ((h >> 43) & kMask) * kUnit - 1, 2 * ((h >> 22) & kMask) * kUnit - 1,
                    2 * ((h >> 1) & kMask) * kUnit - 1};
    });
}

}  // namespace nenrin
