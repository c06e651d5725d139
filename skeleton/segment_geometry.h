#pragma once
/// Closest-point geometry of a point and a line segment, shared by every index implementation
/// (Embree callbacks and the brute-force reference must agree bit for bit).

#include <algorithm>

#include "util/vec3.h"

namespace nenrin {

struct SegmentProjection {
    double tRaw;       ///< unclamped line parameter of the foot point (0 at a, 1 at b)
    double t;          ///< clamped to [0, 1]
    double distance2;  ///< squared distance from the point to the segment
};

inline SegmentProjection projectOntoSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
    Vec3 ab = b - a;
    double len2 = dot(ab, ab);
    double tRaw = len2 > 0 ? dot(p - a, ab) / len2 : 0.0;
    double t = std::clamp(tRaw, 0.0, 1.0);
    Vec3 d = p - (a + ab * t);
    return {tRaw, t, dot(d, d)};
}

}  // namespace nenrin
