/// The growth time of one path (eq. 1-3', 7-10) and of a chain with the joint blend of eq. 4;
/// docs/model.md, "The growth time of one path" and "Polyline joints".

#include "grain/path_time.h"

#include <algorithm>
#include <cmath>

#include "grain/field_bounds.h"
#include "grain/growth_field.h"
#include "grain/growth_terms.h"
#include "skeleton/segment_geometry.h"

namespace nenrin {

double GrowthField::thickening(uint32_t segment, double Ta, const Vec3& d, double distance) const {
    // Eq. 3/3': Tb = Db / S with S = Sb gamma (x taper, x direction).
    const FieldSegment& s = segments_[segment];
    double db = distance;
    double speedFactor = taperFactorFromLog(Ta, params_.taper.nu, taperLogOmega_);
    // The outward normal only matters to the direction term and the radial jitter.
    if (params_.direction.strength != 0 || sway_.radialJitter != 0) {
        Vec3 n = distance > 0 ? d * (1 / distance) : Vec3{};
        speedFactor *= directionFactor(n, params_.direction.sunRay, params_.direction.strength);
        if (sway_.radialJitter != 0) db *= swayRadialFactor(n, swayFrames_[segment], Ta, sway_);
    }
    double Tb = ageWarp(thickeningTime(db, s.inverseSpeed, speedFactor), params_.age.delta);
    if (!radialGrowth_.empty()) Tb = radialGrowth_.arrivalTime(Ta, Tb) - Ta;
    return Tb;
}

GrowthField::PathTime GrowthField::chainPathTime(uint32_t segmentId, const Vec3& p) const {
    return chainPathTime(segmentId, p, project(segments_[segmentId], p));
}

GrowthField::PathTime GrowthField::blendedPathTime(uint32_t segmentId, const Vec3& p, double tRaw,
                                                   double previousT, double nextT) const {
    // Eq. 4, weights = distances to the planes through the shared joints, perpendicular to
    // each segment, over the members in chain order.
    const FieldSegment& s = segments_[segmentId];
    struct Member {
        uint32_t id;
        double tRaw, length;
    };
    Member members[3];
    int count = 0;
    if (previousT >= 0) {
        const uint32_t id = static_cast<uint32_t>(s.previous);
        members[count++] = {id, previousT, segments_[id].length};
    }
    members[count++] = {segmentId, tRaw, s.length};
    if (nextT >= 0) {
        const uint32_t id = static_cast<uint32_t>(s.next);
        members[count++] = {id, nextT, segments_[id].length};
    }
    PathTime own{};
    double times[3], planeDistances[3];
    for (int i = 0; i < count; ++i) {
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

}  // namespace nenrin
