/// The growth time of one path (eq. 1-3', 7-10) and of a chain with the joint blend of eq. 4;
/// docs/model.md, "The growth time of one path" and "Polyline joints".

#include <algorithm>
#include <cmath>

#include "grain/field_bounds.h"
#include "grain/growth_field.h"
#include "grain/growth_terms.h"
#include "skeleton/segment_geometry.h"

namespace nenrin {

double GrowthField::thickening(const FieldSegment& s, double Ta, const Vec3& d,
                               double distance) const {
    // Eq. 3/3': Tb = Db / S with S = Sb gamma (x taper, x direction).
    double db = distance;
    double speedFactor = taperFactor(Ta, params_.taper.nu, params_.taper.omega);
    // The outward normal only matters to the direction term and the radial jitter.
    if (params_.direction.strength != 0 || sway_.radialJitter != 0) {
        Vec3 n = distance > 0 ? d * (1 / distance) : Vec3{};
        speedFactor *= directionFactor(n, params_.direction.sunRay, params_.direction.strength);
        if (sway_.radialJitter != 0) db *= swayRadialFactor(n, s.axis, Ta, sway_);
    }
    double Tb = ageWarp(thickeningTime(db, s.inverseSpeed, speedFactor), params_.age.delta);
    if (!radialGrowth_.empty()) Tb = radialGrowth_.arrivalTime(Ta, Tb) - Ta;
    return Tb;
}

GrowthField::PathTime GrowthField::segmentPathTime(uint32_t segmentId, const Vec3& p,
                                                   double t) const {
    const FieldSegment& s = segments_[segmentId];
    PathTime r;
    r.axisPoint = s.a + s.ab * t;
    r.axisDirection = s.axis;
    r.Ta = elongationTime(s.birthA, s.birthDelta, t);  // eq. 2
    Vec3 d = p - r.axisPoint;
    r.distance = length(d);
    r.Tb = plainThickening_ ? r.distance * s.inverseSpeed : thickening(s, r.Ta, d, r.distance);
    r.T = r.Ta + r.Tb;
    if (s.branch) r.T = dieback(r.T, s.deathTime, s.diebackExponent);
    return r;
}

GrowthField::PathTime GrowthField::chainPathTime(uint32_t segmentId, const Vec3& p) const {
    return chainPathTime(segmentId, p, project(segments_[segmentId], p));
}

GrowthField::PathTime GrowthField::chainPathTime(uint32_t segmentId, const Vec3& p,
                                                 const SegmentProjection& proj) const {
    const FieldSegment& s = segments_[segmentId];
    bool inSlab = proj.tRaw >= 0 && proj.tRaw <= 1;
    // Regions A/B (inside one segment's slab) and C (beyond the joint on the convex side: the
    // clamped nearest point is the joint Q) need no blend.
    if (!inSlab) return segmentPathTime(segmentId, p, proj.t);

    // Region D: P also lies in a neighbour's slab -> eq. 4, weights = distances to the planes
    // through the shared joints, perpendicular to each segment.
    struct Member {
        uint32_t id;
        double tRaw, length;
    };
    Member members[3];
    int count = 0;
    auto slabMember = [&](int32_t id) -> bool {
        if (id == kNone) return false;
        const FieldSegment& x = segments_[static_cast<uint32_t>(id)];
        SegmentProjection px = project(x, p);
        if (px.tRaw < 0 || px.tRaw > 1) return false;
        members[count++] = {static_cast<uint32_t>(id), px.tRaw, x.length};
        return true;
    };
    bool hasPrevious = slabMember(s.previous);
    members[count++] = {segmentId, proj.tRaw, s.length};
    bool hasNext = slabMember(s.next);
    if (!hasPrevious && !hasNext) return segmentPathTime(segmentId, p, proj.tRaw);

    PathTime own{};
    double times[3], planeDistances[3];
    for (int i = 0; i < count; ++i) {  // in chain order
        const Member& m = members[i];
        double w = kInf;
        if (i > 0) w = std::min(w, m.tRaw * m.length);                // joint with previous
        if (i + 1 < count) w = std::min(w, (1 - m.tRaw) * m.length);  // joint with next
        PathTime pt = segmentPathTime(m.id, p, m.tRaw);
        if (m.id == segmentId) own = pt;
        times[i] = pt.T;
        planeDistances[i] = w;
    }
    const size_t n = static_cast<size_t>(count);
    own.T = jointBlend({times, n}, {planeDistances, n}, own.T);
    return own;
}

double GrowthField::radiusAtTime(uint32_t segmentId, const PathTime& path, double time) const {
    // The constant-speed thickening years after which a point born at Ta is reached at `time`
    // (segmentPathTime backwards); they are proportional to the distance along the ray.
    auto years = [&](double t) {
        double warped = t - path.Ta;
        if (!radialGrowth_.empty())
            warped = (radialGrowth_.cumulative(t) - radialGrowth_.cumulative(path.Ta)) /
                     params_.radialSpeed;
        return warped > 0 ? ageUnwarp(warped, params_.age.delta) : 0.0;
    };
    const double target = years(time), here = years(path.Ta + path.Tb);
    if (here > 1e-12 && path.distance > 0) return path.distance * (target / here);
    return target / segments_[segmentId].inverseSpeed;  // on the axis: the nominal speed
}

}  // namespace nenrin
