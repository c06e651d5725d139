#pragma once
/// A rotation plus translation, named destination-from-source (worldFromObject,
/// treeFromLamella): the columns are the source axes seen in the destination frame.

#include <cmath>
#include <numbers>

#include "util/vec3.h"

namespace nenrin {

struct RigidTransform {
    Vec3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};  ///< images of the source axes (orthonormal)
    Vec3 origin;                              ///< image of the source origin

    Vec3 vector(const Vec3& v) const { return x * v.x + y * v.y + z * v.z; }
    Vec3 point(const Vec3& p) const { return origin + vector(p); }
    /// The inverse maps destination to source: transpose of the rotation.
    RigidTransform inverse() const {
        RigidTransform t;
        t.x = {x.x, y.x, z.x};
        t.y = {x.y, y.y, z.y};
        t.z = {x.z, y.z, z.z};
        t.origin = -t.vector(origin);
        return t;
    }
    /// (this o other): applies `other` first.
    RigidTransform operator*(const RigidTransform& other) const {
        RigidTransform t;
        t.x = vector(other.x);
        t.y = vector(other.y);
        t.z = vector(other.z);
        t.origin = point(other.origin);
        return t;
    }

    static RigidTransform translation(const Vec3& t) {
        RigidTransform r;
        r.origin = t;
        return r;
    }
    /// Rotation by `radians` about a unit axis (right-handed).
    static RigidTransform rotation(const Vec3& axis, double radians) {
        double c = std::cos(radians), s = std::sin(radians), k = 1 - c;
        const Vec3& a = axis;
        RigidTransform r;
        r.x = {c + a.x * a.x * k, a.y * a.x * k + a.z * s, a.z * a.x * k - a.y * s};
        r.y = {a.x * a.y * k - a.z * s, c + a.y * a.y * k, a.z * a.y * k + a.x * s};
        r.z = {a.x * a.z * k + a.y * s, a.y * a.z * k - a.x * s, c + a.z * a.z * k};
        return r;
    }
    /// Axes given directly (must be orthonormal and right-handed).
    static RigidTransform fromAxes(const Vec3& x, const Vec3& y, const Vec3& z, const Vec3& o) {
        return {x, y, z, o};
    }
};

constexpr double radians(double degrees) { return degrees * std::numbers::pi / 180; }

}  // namespace nenrin
