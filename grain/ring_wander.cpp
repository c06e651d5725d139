#include "grain/ring_wander.h"

#include <stdexcept>

namespace nenrin {

namespace {

/// The octaves' sum at p, `noise(k, x, y, z)` giving octave k's valueNoise3.
template <class Noise>
Vec3 wanderSum(const Vec3& p, const WanderParams& w, Noise noise) {
    // Octave k: 2^k finer, 2^-k as strong; the weights sum to `norm`, so each component of
    // the sum lies in [-norm, norm] and the result in [-amplitude, amplitude].
    Vec3 sum;
    double norm = 0, weight = 1;
    double x = p.x / w.wavelength, y = p.y / w.wavelength, z = p.z / w.along;
    for (int k = 0; k < w.octaves; ++k) {
        sum = sum + noise(k, x, y, z) * weight;
        norm += weight;
        weight *= 0.5;
        x *= 2, y *= 2, z *= 2;
    }
    return sum * (w.amplitude / norm);
}

}  // namespace

Vec3 ringWander(const Vec3& p, const WanderParams& w) {
    if (w.amplitude == 0) return {};
    return wanderSum(p, w, [&w](int k, double x, double y, double z) {
        return valueNoise3(w.seed + 7919 * k, x, y, z);
    });
}

RingWander::RingWander(const WanderParams& wander) : w_(wander) {
    if (w_.octaves > int(octaves_.size()))
        throw std::invalid_argument("ring wander: more than 4 octaves");
    for (int k = 0; k < w_.octaves; ++k) octaves_[k] = ValueNoise3Cache(w_.seed + 7919 * k);
}

Vec3 RingWander::operator()(const Vec3& p) {
    if (w_.amplitude == 0) return {};
    return wanderSum(p, w_,
                     [this](int k, double x, double y, double z) { return octaves_[k](x, y, z); });
}

}  // namespace nenrin
