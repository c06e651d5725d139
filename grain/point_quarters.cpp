#include "grain/point_quarters.h"

#include <algorithm>
#include <limits>

namespace nenrin {

void PointQuarters::split(std::span<const Vec3> points, const Vec3& boxLo, const Vec3& boxHi) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    quarterOf.resize(points.size());
    lo.fill({kInf, kInf, kInf});
    hi.fill({-kInf, -kInf, -kInf});
    used.fill(false);
    // The box's sides, longest first.
    const double lower[3] = {boxLo.x, boxLo.y, boxLo.z}, upper[3] = {boxHi.x, boxHi.y, boxHi.z};
    int axes[3] = {0, 1, 2};
    std::sort(axes, axes + 3,
              [&](int a, int b) { return upper[a] - lower[a] > upper[b] - lower[b]; });
    const int a = axes[0], b = axes[1];
    const double longest = upper[a] - lower[a], second = upper[b] - lower[b];
    // A squarish box in four by halving both sides; a long one in four along its length.
    const bool along = second < 0.5 * longest;
    const double midA = 0.5 * (lower[a] + upper[a]), midB = 0.5 * (lower[b] + upper[b]);
    const double quarterA = lower[a] + 0.25 * longest, threeQuartersA = lower[a] + 0.75 * longest;
    for (size_t i = 0; i < points.size(); ++i) {
        const Vec3& p = points[i];
        const double c[3] = {p.x, p.y, p.z};
        const int q = along ? (c[a] > quarterA) + (c[a] > midA) + (c[a] > threeQuartersA)
                            : 2 * (c[a] > midA) + (c[b] > midB);
        quarterOf[i] = static_cast<uint8_t>(q);
        lo[q] = {std::min(lo[q].x, p.x), std::min(lo[q].y, p.y), std::min(lo[q].z, p.z)};
        hi[q] = {std::max(hi[q].x, p.x), std::max(hi[q].y, p.y), std::max(hi[q].z, p.z)};
        used[q] = true;
    }
}

}  // namespace nenrin
