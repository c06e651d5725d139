#include "shader/bark.h"

#include <algorithm>
#include <cmath>

#include "util/axis_frame.h"
#include "util/value_noise.h"

namespace nenrin {

Rgb barkAlbedo(const GrowthSample& s, const Vec3& p) {
    const Vec3 a = normalize(s.axisDirection);
    const Vec3 d = p - s.axisPoint;
    const Vec3 perp = d - a * dot(d, a);
    const double rho = length(perp);
    if (rho < 1e-6) return {0.06, 0.04, 0.03};
    const AxisFrame frame(a);
    const double theta = std::atan2(dot(perp, frame.t), dot(perp, frame.s));
    const double arc = theta * rho, z = dot(p, a);
    // Plates ~12 mm across and ~6 cm long, split by fissures; a finer grain on the plates.
    const double plates = valueNoise(0xba4c, arc / 0.012, z / 0.06, rho / 0.01);
    const double fine = valueNoise(0xba4d, arc / 0.002, z / 0.008, 0);
    const double plate = std::clamp((plates + 0.15) / 0.35, 0.0, 1.0);
    const Rgb fissure{0.022, 0.016, 0.012}, surface{0.12, 0.092, 0.07};
    return mix(fissure, surface, plate) * (1 + 0.15 * fine);
}

}  // namespace nenrin
