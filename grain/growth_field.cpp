#include "grain/growth_field.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "grain/growth_terms.h"
#include "skeleton/segment_geometry.h"

namespace nenrin {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double powP(double x, double p) { return p == 2.0 ? x * x : std::pow(x, p); }

/// Nearest of the candidate segments (sorted by id) to p, within maxDistance2. Ties go to the
/// smaller id, like the indexes.
struct Best {
    int32_t segment = kNone;
    double distance2 = kInf;
};

}  // namespace

GrowthField::GrowthField(const SkeletonIndex& index, const GrainParams& params)
    : index_(&index), params_(params) {
    if (index.skeleton().empty() || index.trunk().size() == 0)
        throw std::invalid_argument("GrowthField: the skeleton has no trunk");
    maxSpeed_ = (1 + params_.taper.nu) * (1 + params_.direction.strength);
}

GrowthField::PathTime GrowthField::segmentPathTime(uint32_t segmentId, const Vec3& p,
                                                   double t) const {
    const Skeleton& sk = skeleton();
    const SkeletonSegment& s = sk.segment(segmentId);
    const SkeletonNode& a = sk.node(s.from);
    const SkeletonNode& b = sk.node(s.to);
    PathTime r;
    r.axisPoint = lerp(a.position, b.position, t);
    r.axisDirection = normalize(b.position - a.position);
    r.Ta = a.birthTime + (b.birthTime - a.birthTime) * t;
    Vec3 d = p - r.axisPoint;
    r.distance = length(d);
    Vec3 n = r.distance > 0 ? d / r.distance : Vec3{};
    double speed = params_.radialSpeed * s.gamma *
                   taperFactor(r.Ta, params_.taper.nu, params_.taper.omega) *
                   directionFactor(n, params_.direction.sunRay, params_.direction.strength);
    double db = r.distance * swayRadialFactor(n, r.axisDirection, r.Ta, params_.sway);
    r.Tb = ageWarp(thickeningTime(db, speed), params_.age.delta);
    r.T = r.Ta + r.Tb;
    r.dead = false;
    if (s.kind == SegmentKind::Branch && r.T > s.deathTime) {
        r.T = dieback(r.T, s.deathTime, s.diebackExponent);
        r.dead = true;
    }
    return r;
}

GrowthField::PathTime GrowthField::chainPathTime(uint32_t segmentId, const Vec3& p) const {
    const Skeleton& sk = skeleton();
    const SkeletonSegment& s = sk.segment(segmentId);
    SegmentProjection proj = projectOntoSegment(p, sk.start(s), sk.end(s));
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
        const SkeletonSegment& x = sk.segment(static_cast<uint32_t>(id));
        SegmentProjection px = projectOntoSegment(p, sk.start(x), sk.end(x));
        if (px.tRaw < 0 || px.tRaw > 1) return false;
        members[count++] = {static_cast<uint32_t>(id), px.tRaw, length(sk.end(x) - sk.start(x))};
        return true;
    };
    bool hasPrevious = slabMember(s.previous);
    members[count++] = {segmentId, proj.tRaw, length(sk.end(s) - sk.start(s))};
    bool hasNext = slabMember(s.next);
    if (!hasPrevious && !hasNext) return segmentPathTime(segmentId, p, proj.tRaw);

    PathTime own{};
    double weighted = 0, weights = 0;
    for (int i = 0; i < count; ++i) {  // chain order: the sum is the same from either side
        const Member& m = members[i];
        double w = kInf;
        if (i > 0) w = std::min(w, m.tRaw * m.length);                // joint with previous
        if (i + 1 < count) w = std::min(w, (1 - m.tRaw) * m.length);  // joint with next
        PathTime pt = segmentPathTime(m.id, p, m.tRaw);
        if (m.id == segmentId) own = pt;
        weighted += w * pt.T;
        weights += w;
    }
    if (weights > 0) own.T = weighted / weights;
    return own;
}

double GrowthField::branchSearchRadius(double trunkTime) const {
    // A branch path at distance D has T_c >= (D (1 - jitter) / (gamma Sb maxSpeed))^delta; once
    // that reaches reach x T1 its weight is 0, so farther segments need not be looked at.
    double gamma = skeleton().maxBranchGamma();
    double years =
        std::pow(params_.junction.reach * std::max(trunkTime, 0.0), 1.0 / params_.age.delta);
    return gamma * params_.radialSpeed * maxSpeed_ * years / (1 - params_.sway.radialJitter);
}

GrowthSample GrowthField::evaluate(const Vec3& p) const {
    GrowthScratch scratch;
    GrowthSample out;
    evaluateBatch({&p, 1}, {&out, 1}, scratch);
    return out;
}

void GrowthField::evaluateBatch(std::span<const Vec3> input, std::span<GrowthSample> out,
                                GrowthScratch& scratch) const {
    const size_t n = input.size();
    if (n == 0) return;
    const Skeleton& sk = skeleton();
    auto& pts = scratch.points;
    pts.resize(n);
    Vec3 lo{kInf, kInf, kInf}, hi = -lo;
    for (size_t i = 0; i < n; ++i) {
        pts[i] = input[i] + swayDisplacement(input[i], params_.sway);
        lo = {std::min(lo.x, pts[i].x), std::min(lo.y, pts[i].y), std::min(lo.z, pts[i].z)};
        hi = {std::max(hi.x, pts[i].x), std::max(hi.y, pts[i].y), std::max(hi.z, pts[i].z)};
    }
    const Vec3 centre = (lo + hi) * 0.5;
    const double halfDiagonal = 0.5 * length(hi - lo);

    // Trunk: every point of the batch is within d0 + h of some trunk segment, so its nearest
    // trunk segment is within d0 + 2h of the centre.
    NearestSegment near = index_->trunk().nearest(centre);
    auto& trunkCands = scratch.trunkCandidates;
    trunkCands.clear();
    index_->trunk().gather(centre, std::sqrt(near.distance2) + 2 * halfDiagonal + 1e-9, trunkCands);
    std::sort(trunkCands.begin(), trunkCands.end());

    double maxTrunkTime = 0;
    for (size_t i = 0; i < n; ++i) {
        const Vec3& p = pts[i];
        Best best;
        for (uint32_t id : trunkCands) {
            const auto& s = sk.segment(id);
            double d2 = projectOntoSegment(p, sk.start(s), sk.end(s)).distance2;
            if (d2 < best.distance2) best = {static_cast<int32_t>(id), d2};
        }
        PathTime trunk = chainPathTime(static_cast<uint32_t>(best.segment), p);
        GrowthSample& g = out[i];
        g = GrowthSample{};
        g.T = g.trunkTime = trunk.T;
        g.Ta = trunk.Ta;
        g.Tb = trunk.Tb;
        g.axisPoint = trunk.axisPoint;
        g.axisDirection = trunk.axisDirection;
        maxTrunkTime = std::max(maxTrunkTime, trunk.T);
    }
    if (index_->branches().size() == 0) return;

    auto& branchCands = scratch.branchCandidates;
    branchCands.clear();
    index_->branches().gather(centre, branchSearchRadius(maxTrunkTime) + halfDiagonal + 1e-9,
                              branchCands);
    if (branchCands.empty()) return;
    std::sort(branchCands.begin(), branchCands.end());

    const double p = params_.junction.p;
    for (size_t i = 0; i < n; ++i) {
        const Vec3& pt = pts[i];
        GrowthSample& g = out[i];
        const double t1 = g.trunkTime;
        const double radius = branchSearchRadius(t1);
        const double radius2 = radius * radius;
        auto& terms = scratch.terms;
        terms.clear();
        // Candidates are sorted by id and ids are contiguous per chain: one pass finds each
        // chain's nearest segment within the radius.
        size_t k = 0;
        while (k < branchCands.size()) {
            uint32_t chain = sk.segment(branchCands[k]).chain;
            Best best;
            for (; k < branchCands.size() && sk.segment(branchCands[k]).chain == chain; ++k) {
                const auto& s = sk.segment(branchCands[k]);
                double d2 = projectOntoSegment(pt, sk.start(s), sk.end(s)).distance2;
                if (d2 <= radius2 && d2 < best.distance2)
                    best = {static_cast<int32_t>(branchCands[k]), d2};
            }
            if (best.segment == kNone) continue;
            // alpha: angle between QP and the plane F through the branch start Q,
            // perpendicular to the branch (eq. 5).
            const SkeletonChain& c = sk.chain(chain);
            const SkeletonSegment& first = sk.segment(c.firstSegment);
            Vec3 q = sk.start(first);
            Vec3 v = pt - q;
            double lv = length(v);
            double sinAlpha = lv > 0 ? dot(v, normalize(sk.end(first) - q)) / lv : 0;
            if (sinAlpha <= 0) continue;
            PathTime bp = chainPathTime(static_cast<uint32_t>(best.segment), pt);
            if (junctionReachWeight(bp.T, t1, params_.junction.reach) <= 0) continue;
            // A dead knot: the branch had died before the trunk's bark reached P, so P lies in
            // the dead stub that the trunk encased.
            bool dead = t1 > sk.segment(static_cast<uint32_t>(best.segment)).deathTime;
            terms.push_back({chain, bp.T, sinAlpha, bp.distance, dead});
        }
        if (terms.empty()) continue;

        // Smooth minimum, normalised by the smallest candidate time so large p cannot overflow.
        double m = t1;
        for (const auto& t : terms) m = std::min(m, t.time / t.sinAlpha);
        if (m <= 0) {
            g.T = 0;
            continue;
        }
        double trunkTerm = powP(m / t1, p);
        double sum = trunkTerm, dead = 0, strongest = 0;
        for (const auto& t : terms) {
            double u = junctionReachWeight(t.time, t1, params_.junction.reach) *
                       powP(m * t.sinAlpha / t.time, p);
            sum += u;
            if (t.dead) dead += u;
            if (u > strongest) {
                strongest = u;
                g.knotChain = static_cast<int32_t>(t.chain);
                g.knotAxisDistance = t.distance;
            }
        }
        g.T = m * (p == 2.0 ? 1.0 / std::sqrt(sum) : std::pow(sum, -1.0 / p));
        g.knot = (sum - trunkTerm) / sum;
        g.deadKnot = dead / sum;
    }
}

}  // namespace nenrin
