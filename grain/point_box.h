#pragma once
/// An axis-aligned box around points: a chunk's, a quarter's, a chain's kept segments'.

#include <algorithm>
#include <limits>
#include <span>

#include "util/vec3.h"

namespace nenrin {

struct PointBox {
    static constexpr double kFar = std::numeric_limits<double>::infinity();
    Vec3 lo{kFar, kFar, kFar}, hi{-kFar, -kFar, -kFar};  ///< empty until a point is added
    void add(const Vec3& p) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    void add(const PointBox& b) {
        lo = {std::min(lo.x, b.lo.x), std::min(lo.y, b.lo.y), std::min(lo.z, b.lo.z)};
        hi = {std::max(hi.x, b.hi.x), std::max(hi.y, b.hi.y), std::max(hi.z, b.hi.z)};
    }
    bool empty() const { return !(lo.x <= hi.x); }
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

/// The box around boxes (the same as around all their points: min and max are exact).
inline PointBox boxOf(std::span<const PointBox> boxes) {
    PointBox b;
    for (const PointBox& x : boxes) b.add(x);
    return b;
}

}  // namespace nenrin
