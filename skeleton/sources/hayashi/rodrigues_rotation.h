#pragma once
/// Rotation of a vector about an arbitrary axis (Rodrigues' formula), used by the Hayashi &
/// Takahashi tree model to turn side branches by an angle beta about their parent's axis.
///
/// The paper (section 4.2 (2), after Nakamae & Nishita 1991) prints the 3x3 matrix with typos;
/// this is the textbook form. Positive angles turn counter-clockwise when the axis points at the
/// viewer (right-hand rule).

#include <cmath>

#include "util/vec3.h"

namespace nenrin {

/// `v` rotated by `angle` (radians) about the unit vector `unitAxis` through the origin:
/// v cos b + (k x v) sin b + k (k . v)(1 - cos b).
inline Vec3 rotateAboutAxis(const Vec3& v, const Vec3& unitAxis, double angle) {
    double c = std::cos(angle), s = std::sin(angle);
    return v * c + cross(unitAxis, v) * s + unitAxis * (dot(unitAxis, v) * (1 - c));
}

/// A unit direction at `elongationAngle` (radians) from the unit `parentAxis`, turned by `beta`
/// about it: the side branch of Fig. 18 (alpha = angle to the parent, beta = turn around it).
/// beta = 0 is the side of the parent that faces up (or +X for a vertical parent), so a given
/// beta means the same thing on every parent.
inline Vec3 sideBranchDirection(const Vec3& parentAxis, double elongationAngle, double beta) {
    Vec3 up{0, 0, 1};
    Vec3 side = cross(cross(parentAxis, up), parentAxis);  // up, made perpendicular to the axis
    if (lengthSquared(side) < 1e-20) side = anyPerpendicular(parentAxis);
    side = normalize(side);
    Vec3 start = parentAxis * std::cos(elongationAngle) + side * std::sin(elongationAngle);
    return normalize(rotateAboutAxis(start, parentAxis, beta));
}

}  // namespace nenrin
