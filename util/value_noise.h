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

/// Where (x, y, z) lies in the unit lattice: its cell's lowest corner and the smoothstep
/// weights along each axis.
struct LatticeCell {
    long long ix, iy, iz;
    double tx, ty, tz;
};

inline LatticeCell latticeCell(double x, double y, double z) {
    const double fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
    auto s = [](double t) { return t * t * (3 - 2 * t); };
    return {(long long)fx, (long long)fy, (long long)fz, s(x - fx), s(y - fy), s(z - fz)};
}

/// Trilinear interpolation between a cell's eight corner values, corner c at offset
/// (c & 1, c >> 1 & 1, c >> 2 & 1).
template <class T>
inline T blendCorners(const LatticeCell& l, const T* corners) {
    T v{};
    for (int c = 0; c < 8; ++c) {
        const int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
        const double w = (dx ? l.tx : 1 - l.tx) * (dy ? l.ty : 1 - l.ty) * (dz ? l.tz : 1 - l.tz);
        v = v + corners[c] * w;
    }
    return v;
}

/// Trilinear, smoothstep-weighted interpolation between the values `corner(a, b, c)` gives at
/// the eight lattice points around (x, y, z); T is double or Vec3.
template <class T, class Corner>
inline T smoothLattice(double x, double y, double z, Corner corner) {
    const LatticeCell l = latticeCell(x, y, z);
    T corners[8];
    for (int c = 0; c < 8; ++c)
        corners[c] = corner(l.ix + (c & 1), l.iy + ((c >> 1) & 1), l.iz + ((c >> 2) & 1));
    return blendCorners(l, corners);
}

/// The value at lattice corner (a, b, c): 2 cellRandom(seed, 11, a, b, c) - 1.
inline double valueNoiseCorner(uint64_t seed, long long a, long long b, long long c) {
    return 2 * cellRandom(seed, 11, a, b, c) - 1;
}

/// smoothLattice of valueNoiseCorner, bit for bit, with the hashing the eight corners share
/// done once: cellRandom's hash is mix(mix(s ^ mix(key(a, b))) ^ mix(c)) with s = hashCombine(
/// seed, 11), and the corners have four keys and two c's, so 20 mixes instead of 34 (the wood's
/// anatomy calls this ~40 times a pixel).
inline double valueNoise(uint64_t seed, double x, double y, double z) {
    const LatticeCell l = latticeCell(x, y, z);
    const uint64_t s = hashCombine(seed, 11);
    uint64_t column[4];  // per (a, b): hashCombine(s, key(a, b))
    for (int k = 0; k < 4; ++k)
        column[k] = hashCombine(s, static_cast<uint64_t>(l.ix + (k & 1)) * 0x9E3779B97F4A7C15ull ^
                                       static_cast<uint64_t>(l.iy + (k >> 1)));
    const uint64_t level[2] = {mix64(static_cast<uint64_t>(l.iz)),
                               mix64(static_cast<uint64_t>(l.iz + 1))};
    double corners[8];
    for (int c = 0; c < 8; ++c)
        corners[c] =
            2 * (static_cast<double>(mix64(column[c & 3] ^ level[c >> 2]) >> 11) * 0x1.0p-53) - 1;
    return blendCorners(l, corners);
}

/// The lattice value of valueNoise3 at corner (a, b, c); `base` = hashCombine(seed, 13).
inline Vec3 valueNoise3Corner(uint64_t base, long long a, long long b, long long c) {
    constexpr double kUnit = 0x1.0p-21;
    constexpr uint64_t kMask = (uint64_t(1) << 21) - 1;
    // Each coordinate hashed in turn: a key such as (a G) ^ b (cellRandom's) gives (a, b) and
    // (-a, -b) the same value a third of the time, and rings would mirror across the pith.
    const uint64_t h = hashCombine(
        hashCombine(hashCombine(base, static_cast<uint64_t>(a)), static_cast<uint64_t>(b)),
        static_cast<uint64_t>(c));
    return Vec3{2 * ((h >> 43) & kMask) * kUnit - 1, 2 * ((h >> 22) & kMask) * kUnit - 1,
                2 * ((h >> 1) & kMask) * kUnit - 1};
}

/// Three independent value noises at once, each in [-1, 1]: one hash per lattice corner gives
/// all three (21 bits each), a third of the hashing of three valueNoise calls. For smooth
/// displacements (ring wander) evaluated many times per sample.
inline Vec3 valueNoise3(uint64_t seed, double x, double y, double z) {
    const uint64_t base = hashCombine(seed, 13);
    return smoothLattice<Vec3>(x, y, z, [base](long long a, long long b, long long c) {
        return valueNoise3Corner(base, a, b, c);
    });
}

/// valueNoise3 of one seed at many nearby points: the last cell's corner values are kept, so
/// a point in the same cell as the one before hashes nothing (a tile of samples, or a gradient
/// stencil, mostly lies in one cell of a centimetre-scale lattice). The same bits as
/// valueNoise3.
class ValueNoise3Cache {
public:
    explicit ValueNoise3Cache(uint64_t seed = 0) : base_(hashCombine(seed, 13)) {}
    Vec3 operator()(double x, double y, double z) {
        const LatticeCell l = latticeCell(x, y, z);
        if (!valid_ || l.ix != ix_ || l.iy != iy_ || l.iz != iz_) {
            for (int c = 0; c < 8; ++c)
                corners_[c] = valueNoise3Corner(base_, l.ix + (c & 1), l.iy + ((c >> 1) & 1),
                                                l.iz + ((c >> 2) & 1));
            ix_ = l.ix, iy_ = l.iy, iz_ = l.iz;
            valid_ = true;
        }
        return blendCorners(l, corners_);
    }

private:
    uint64_t base_;
    bool valid_ = false;
    long long ix_ = 0, iy_ = 0, iz_ = 0;
    Vec3 corners_[8];
};

}  // namespace nenrin
