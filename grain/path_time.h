#pragma once
/// The growth time of one path (eq. 1-3', 7-10) and the test for a chain's joint blend (eq.
/// 4), inline: the trunk and branch passes take them once per point and path, most points
/// needing neither a blend nor more than the plain thickening. The blend itself is
/// GrowthField::blendedPathTime (path_time.cpp). Internal to grain/.

#include "grain/growth_field.h"
#include "grain/growth_terms.h"

namespace nenrin {

inline GrowthField::PathTime GrowthField::segmentPathTime(uint32_t segmentId, const Vec3& p,
                                                          double t) const {
    const FieldSegment& s = segments_[segmentId];
    PathTime r;
    r.axisPoint = s.a + s.ab * t;
    r.axisDirection = s.axis;
    r.Ta = elongationTime(s.birthA, s.birthDelta, t);  // eq. 2
    Vec3 d = p - r.axisPoint;
    r.distance = length(d);
    r.Tb =
        plainThickening_ ? r.distance * s.inverseSpeed : thickening(segmentId, r.Ta, d, r.distance);
    r.T = r.Ta + r.Tb;
    if (s.branch) r.T = dieback(r.T, s.deathTime, s.diebackExponent);
    return r;
}

inline GrowthField::PathTime GrowthField::chainPathTime(uint32_t segmentId, const Vec3& p,
                                                        const SegmentProjection& proj) const {
    const FieldSegment& s = segments_[segmentId];
    // Regions A/B (inside one segment's slab) and C (beyond the joint on the convex side: the
    // clamped nearest point is the joint Q) need no blend.
    if (!(proj.tRaw >= 0 && proj.tRaw <= 1)) return segmentPathTime(segmentId, p, proj.t);
    // Region D: P also lies in a neighbour's slab. Only project()'s tRaw decides that, so the
    // neighbours are tested with it alone: most points are in neither, and pay just this.
    auto slabParameter = [&](int32_t id, double& tRaw) {
        if (id == kNone) return false;
        const FieldSegment& x = segments_[static_cast<uint32_t>(id)];
        tRaw = dot(p - x.a, x.ab) * x.invLength2;
        return tRaw >= 0 && tRaw <= 1;
    };
    double previousT = -1, nextT = -1;
    const bool hasPrevious = slabParameter(s.previous, previousT);
    const bool hasNext = slabParameter(s.next, nextT);
    if (!hasPrevious && !hasNext) return segmentPathTime(segmentId, p, proj.tRaw);
    return blendedPathTime(segmentId, p, proj.tRaw, hasPrevious ? previousT : -1,
                           hasNext ? nextT : -1);
}

inline double GrowthField::radiusAtTime(uint32_t segmentId, double Ta, double Tb, double distance,
                                        double time) const {
    // The constant-speed thickening years after which a point born at Ta is reached at `time`
    // (segmentPathTime backwards); they are proportional to the distance along the ray.
    auto years = [&](double t) {
        double warped = t - Ta;
        if (!radialGrowth_.empty())
            warped =
                (radialGrowth_.cumulative(t) - radialGrowth_.cumulative(Ta)) / params_.radialSpeed;
        return warped > 0 ? ageUnwarp(warped, params_.age.delta) : 0.0;
    };
    const double target = years(time), here = years(Ta + Tb);
    if (here > 1e-12 && distance > 0) return distance * (target / here);
    return target / segments_[segmentId].inverseSpeed;  // on the axis: the nominal speed
}

}  // namespace nenrin
