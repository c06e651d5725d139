#include "grain/point_warp.h"

#include <algorithm>
#include <cmath>

namespace nenrin {

Vec3 pointWarp(const Vec3& p, const WarpParams& w) {
    if (!w.enabled()) return {};
    // Per axis: the cell, the fraction across it, and the fade outside the lattice.
    struct Axis {
        int i0;
        double f, fade;
    };
    auto axis = [](double x, double origin, double step, int n) {
        const double u = (x - origin) / step, last = double(n - 1);
        const double outside = u < 0 ? -u : (u > last ? u - last : 0.0);
        const double fade = std::max(0.0, 1 - outside);
        const double c = std::clamp(u, 0.0, last);
        const int i0 = std::min(int(std::floor(c)), n - 2);
        return Axis{i0, c - i0, fade};
    };
    const Axis ax = axis(p.x, w.origin.x, w.step.x, w.nx);
    const Axis ay = axis(p.y, w.origin.y, w.step.y, w.ny);
    const Axis az = axis(p.z, w.origin.z, w.step.z, w.nz);
    const double fade = ax.fade * ay.fade * az.fade;
    if (fade <= 0) return {};
    Vec3 sum;
    for (int corner = 0; corner < 8; ++corner) {
        const int dx = corner & 1, dy = (corner >> 1) & 1, dz = corner >> 2;
        const double weight =
            (dx ? ax.f : 1 - ax.f) * (dy ? ay.f : 1 - ay.f) * (dz ? az.f : 1 - az.f);
        const size_t node = size_t(((az.i0 + dz) * w.ny + (ay.i0 + dy)) * w.nx + (ax.i0 + dx));
        sum = sum + w.displacement[node] * weight;
    }
    return sum * fade;
}

}  // namespace nenrin
