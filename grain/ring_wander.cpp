#include "grain/ring_wander.h"

#include "util/value_noise.h"

namespace nenrin {

Vec3 ringWander(const Vec3& p, const WanderParams& w) {
    if (w.amplitude == 0) return {};
    // Octave k: 2^k finer, 2^-k as strong; the weights sum to `norm`, so each component of
    // the sum lies in [-norm, norm] and the result in [-amplitude, amplitude].
    Vec3 sum;
    double norm = 0, weight = 1;
    double x = p.x / w.wavelength, y = p.y / w.wavelength, z = p.z / w.along;
    for (int k = 0; k < w.octaves; ++k) {
        sum = sum + valueNoise3(w.seed + 7919 * k, x, y, z) * weight;
        norm += weight;
        weight *= 0.5;
        x *= 2, y *= 2, z *= 2;
    }
    return sum * (w.amplitude / norm);
}

}  // namespace nenrin
