/// The growth field's branch pass: each point's branch paths among a chunk's tile chains and
/// their junction blend with its trunk path (eq. 5; docs/model.md, "How evaluation is
/// organised", steps 5 and 6), and the knot the blend makes.

#include <algorithm>
#include <cmath>
#include <span>

#include "grain/field_bounds.h"
#include "grain/field_passes.h"
#include "grain/growth_field.h"
#include "grain/growth_terms.h"

namespace nenrin {

namespace {

/// Up to this many kept segments of a chain, a point measures them in double one by one: the
/// vectorised float pass only pays beyond.
constexpr uint32_t kDirectScan = 12;

/// What the cheap tests of a branch path read of the field.
struct ReachBounds {
    std::span<const FieldSegment> segments;
    double speedBound;  ///< GrowthField::speedBound_
    double delta;       ///< of the age warp, eq. 8
    double reach;       ///< of the junction's cut-off
};

/// The nearest to p of the kept segments [begin, end): a few (the usual case) measured in
/// double directly, more in one vectorised float pass with near-ties settled in double. Both
/// give the smallest double distance, ties to the first (smaller id).
Best nearestKeptSegment(std::span<const FieldSegment> segments, SegmentBatch& kept, uint32_t begin,
                        uint32_t end, const Vec3& p) {
    Best best;
    if (end - begin <= kDirectScan) {
        for (uint32_t k = begin; k < end; ++k) {
            const double d2 = project(segments[kept.id(k)], p).distance2;
            if (d2 < best.distance2) best = {static_cast<int32_t>(kept.id(k)), d2};
        }
        return best;
    }
    const SegmentBatch::Measured measured = kept.measureFrom(p, begin, end);
    const uint32_t nearest = kept.id(kept.nearest(begin, end, measured, [&](uint32_t k) {
        return project(segments[kept.id(k)], p).distance2;
    }));
    return {static_cast<int32_t>(nearest), project(segments[nearest], p).distance2};
}

/// A chain's path that may come in under reach x T1 sin(alpha) at a point.
struct BranchCandidate {
    double sinAlpha;
    Best nearest;  ///< the chain's nearest kept segment
};

/// The cheap tests of a chain at point p (trunk time t1), before its path time: false if its
/// path cannot come in under reach x T1 sin(alpha) there (weight 0), else the candidate.
bool mayComeUnderReach(const ReachBounds& r, const TileChain& tc, SegmentBatch& kept,
                       uint8_t quarter, const Vec3& p, double t1, BranchCandidate& out) {
    // alpha: angle between QP and the plane F through the branch start Q, perpendicular to
    // the branch (eq. 5). Behind F the branch does not count.
    Vec3 v = p - tc.start;
    double lv = length(v);
    const double sinAlpha = lv > 0 ? dot(v, tc.direction) / lv : 0;
    if (sinAlpha <= 0) return false;
    // Beyond this distance T_c / sin(alpha) is past reach x T1: weight 0.
    double slack = r.reach * t1 * sinAlpha - tc.birthBound;
    if (slack <= 0) return false;
    double radius = tc.gamma * r.speedBound * ageUnwarp(slack, r.delta);
    double radius2 = radius * radius;
    // Quick reject: the box around the chain's kept segments is out of reach.
    Vec3 outside{std::max(std::max(tc.lower.x - p.x, p.x - tc.upper.x), 0.0),
                 std::max(std::max(tc.lower.y - p.y, p.y - tc.upper.y), 0.0),
                 std::max(std::max(tc.lower.z - p.z, p.z - tc.upper.z), 0.0)};
    if (dot(outside, outside) > radius2) return false;
    const Best best = nearestKeptSegment(r.segments, kept, tc.begin[quarter], tc.end[quarter], p);
    if (best.distance2 > radius2) return false;
    out = {sinAlpha, best};
    // The path through the nearest segment cannot come in under reach x T1: skip it before
    // paying for the full path time.
    const FieldSegment& bs = r.segments[static_cast<uint32_t>(best.segment)];
    const double needed = r.reach * t1 * sinAlpha;
    if (bs.birthBound >= needed) return false;
    if (std::isfinite(bs.deathBound)) {
        double bound = bs.birthBound +
                       ageWarp(std::sqrt(best.distance2) / (bs.gammaBound * r.speedBound), r.delta);
        return !(diebackLowerBound(bound, bs.deathBound, bs.diebackBound) >= needed);
    }
    // The same bound for a living branch, as a distance: no square root.
    double reachable = bs.gammaBound * r.speedBound * ageUnwarp(needed - bs.birthBound, r.delta);
    return !(best.distance2 >= reachable * reachable);
}

/// Eq. 5 over the trunk path (the sample's trunk time) and the branch paths `terms`, relative
/// to the smallest effective time, into the sample's T, knot and dead-knot shares; returns the
/// branch path with the largest share (none if no term counts).
const BranchTerm* blendJunction(std::span<const BranchTerm> terms, double p, GrowthSample& g) {
    const double t1 = g.trunkTime;
    double m = t1;
    for (const BranchTerm& t : terms) m = std::min(m, t.time / t.sinAlpha);
    if (m <= 0) {
        g.T = 0;
        return nullptr;
    }
    JunctionSum sum(m, t1, p);
    double dead = 0, strongest = 0;
    const BranchTerm* top = nullptr;
    for (const BranchTerm& t : terms) {
        double u = sum.add(t.time / t.sinAlpha, t.weight);
        dead += t.dead * u;
        if (u > strongest) strongest = u, top = &t;
    }
    g.T = sum.time();
    g.knot = sum.branchShare();
    g.deadKnot = dead / sum.sum();
    return top;
}

}  // namespace

void GrowthField::evaluateBranches(std::span<const Vec3> points, const PointQuarters& quarters,
                                   TileChains& chains, std::span<GrowthSample> out,
                                   std::vector<BranchTerm>& terms) const {
    if (chains.chains.empty()) return;
    const ReachBounds bounds{segments_, speedBound_, params_.age.delta, params_.junction.reach};
    for (size_t i = 0; i < points.size(); ++i) {
        const Vec3& p = points[i];
        GrowthSample& g = out[i];
        const double t1 = g.trunkTime;
        terms.clear();
        const uint8_t quarter = quarters.quarterOf(i);
        for (const TileChain& tc : chains.chains) {
            BranchCandidate c;
            if (!mayComeUnderReach(bounds, tc, chains.segments, quarter, p, t1, c)) continue;
            const uint32_t segment = static_cast<uint32_t>(c.nearest.segment);
            const PathTime path = chainPathTime(segment, p);
            const double weight = junctionReachWeight(path.T / c.sinAlpha, t1, bounds.reach);
            if (weight <= 0) continue;
            // A dead knot: the branch had died before the trunk's bark reached P, so P lies in
            // the dead stub that the trunk encased.
            // The change from intergrown to encased knot is sharp in real wood; one year of
            // trunk growth keeps it from aliasing.
            const double deathTime = segments_[segment].deathTime;
            const double dead =
                std::isfinite(deathTime) ? smoothstep(deathTime - 0.5, deathTime + 0.5, t1) : 0.0;
            terms.push_back({tc.chain, path.T, c.sinAlpha, path.distance, dead, weight, segment,
                             path.axisPoint, path.axisDirection, path.Ta, path.Tb});
        }
        if (terms.empty()) continue;
        if (const BranchTerm* top = blendJunction(terms, params_.junction.p, g))
            describeKnot(*top, p, t1, g);
    }
}

void GrowthField::describeKnot(const BranchTerm& t, const Vec3& point, double trunkTime,
                               GrowthSample& g) const {
    g.knotChain = static_cast<int32_t>(t.chain);
    g.knotAxisDistance = t.distance;
    g.knotOffset = point - t.axisPoint;
    g.knotAxisDirection = t.axisDirection;
    // The knot's edge: the branch's share is one half where w (m / x)^p = (m / T1)^p with
    // x = Tc / sin(alpha), i.e. Tc = T1 sin(alpha) w^(1/p); past the branch's death that time
    // is a dieback'd one, so undo eq. 10 to get back to the time the growth terms give.
    const FieldSegment& s = segments_[t.segment];
    // (w^(1/p) is exactly 1 for w = 1, the usual weight: no pow() for it.)
    const double root = t.weight == 1 ? 1.0 : std::pow(t.weight, 1 / params_.junction.p);
    double edge = trunkTime * t.sinAlpha * root;
    if (edge > s.deathTime)
        edge = s.deathTime * std::pow(edge / s.deathTime, 1 / (1 + s.diebackExponent));
    g.knotDied = t.dead > 0.5;
    PathTime path{t.time, t.Ta, t.Tb, t.axisPoint, t.axisDirection, t.distance};
    g.knotRadius = radiusAtTime(t.segment, path, edge);
}

}  // namespace nenrin
