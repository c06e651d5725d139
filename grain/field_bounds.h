#pragma once
/// Bounds the growth field's culls share: boxes of points and segments, and the dieback of
/// eq. 10 from below and backwards. Internal to grain/.

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "util/vec3.h"

namespace nenrin {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

/// An axis-aligned box: chunk bounds and the bounds of kept segments.
struct PointBox {
    Vec3 lo{kInf, kInf, kInf}, hi{-kInf, -kInf, -kInf};
    void add(const Vec3& p) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    Vec3 centre() const { return (lo + hi) * 0.5; }
    double halfDiagonal() const { return 0.5 * length(hi - lo); }
    /// Corner i of 8 (bit 0: x, bit 1: y, bit 2: z at the upper side). A linear function
    /// takes its extremes over the box at corners.
    Vec3 corner(int i) const {
        return {i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z};
    }
};

inline PointBox boxOf(std::span<const Vec3> points) {
    PointBox b;
    for (const Vec3& p : points) b.add(p);
    return b;
}

/// A lower bound of dieback(t, deathTime, eps) without pow(): (t / Tlim)^eps >= (t / Tlim)^n
/// for n = floor(eps) since t / Tlim >= 1 there.
inline double diebackLowerBound(double t, double deathTime, double eps) {
    if (!(t > deathTime)) return t;
    double x = t / deathTime, factor = 1;
    for (int n = static_cast<int>(std::min(eps, 8.0)); n > 0; --n) factor *= x;
    return t * factor;
}

/// The largest time t whose diebackLowerBound(t, deathTime, eps) can stay under `limit`
/// (rounded up): a path must come in under it before dieback to come in under `limit` after.
inline double diebackBudget(double limit, double deathTime, double eps) {
    if (!(limit > deathTime)) return limit;
    const int n = static_cast<int>(std::min(eps, 8.0));
    if (n <= 0) return limit;
    // t (t / Tlim)^n = limit  <=>  t = Tlim (limit / Tlim)^(1 / (n + 1)); the usual exponents
    // without pow().
    const double x = limit / deathTime;
    const double root = n == 1 ? std::sqrt(x) : n == 2 ? std::cbrt(x) : std::pow(x, 1.0 / (n + 1));
    return deathTime * root * (1 + 1e-9) + 1e-12;
}

}  // namespace nenrin
