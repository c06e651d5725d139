#pragma once
/// An orthonormal frame around a unit axis: the shading frame around a normal, the wood frame
/// around a pith or knot axis. One construction everywhere, so every such frame agrees.

#include "util/vec3.h"

namespace nenrin {

struct AxisFrame {
    Vec3 s, t, n;  ///< s = anyPerpendicular(n), t = n x s: right-handed, n the axis

    AxisFrame() = default;
    /// `axis` must be unit length.
    explicit AxisFrame(const Vec3& axis) : s(anyPerpendicular(axis)), t(cross(axis, s)), n(axis) {}

    Vec3 toLocal(const Vec3& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
    Vec3 toWorld(const Vec3& v) const { return s * v.x + t * v.y + n * v.z; }
};

}  // namespace nenrin
