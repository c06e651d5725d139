#include "grain/ring_wander.h"

#include "util/value_noise.h"

namespace nenrin {

Vec3 ringWander(const Vec3& p, const WanderParams& w) {
    if (w.amplitude == 0) return {};
    // Octave k: 2^k finer, 2^-k as strong; the weights sum to `norm`, so each component of
    // the sum lies in [-norm, norm] and the result in [-amplitude, amplitude].
    double sum[3] = {0, 0, 0}, norm = 0, weight = 1;
    double x = p.x / w.wavelength, y = p.y / w.wavelength, z = p.z / w.along;
    for (int k = 0; k < w.octaves; ++k) {
        for (int axis = 0; axis < 3; ++axis)
            sum[axis] += weight * valueNoise(w.seed * 3 + axis, x, y, z);
        norm += weight;
        weight *= 0.5;
        x *= 2, y *= 2, z *= 2;
    }
    const double scale = w.amplitude / norm;
    return Vec3{sum[0], sum[1], sum[2]} * scale;
}

}  // namespace nenrin
