/// The growth field's branch pass: each point's branch paths among a chunk's tile chains and
/// their junction blend with its trunk path (eq. 5; docs/model.md, "How evaluation is
/// organised", steps 5 and 6), and the knot the blend makes.

#include <algorithm>
#include <cmath>
#include <span>

#include "grain/branch_lanes.h"
#include "grain/field_bounds.h"
#include "grain/field_passes.h"
#include "grain/growth_field.h"
#include "grain/growth_terms.h"
#include "grain/path_time.h"
#include "grain/reach_lanes.h"

namespace nenrin {

namespace {

/// Up to this many kept segments of a chain, a point measures them in double one by one: the
/// vectorised float pass only pays beyond.
constexpr uint32_t kDirectScan = 12;
static_assert(kDirectScan <= kBranchLaneSegments, "branchLanes takes what is scanned directly");

/// The nearest to p of the kept segments [begin, end): a few (the usual case) measured in
/// double directly, more in one vectorised float pass with near-ties settled in double. Both
/// give the smallest double distance, ties to the first (smaller id).
Best nearestKeptSegment(std::span<const FieldSegment> segments, SegmentBatch& kept, uint32_t begin,
                        uint32_t end, const Vec3& p, SegmentProjection& projection) {
    Best best;
    if (end - begin <= kDirectScan) {
        for (uint32_t k = begin; k < end; ++k) {
            const SegmentProjection x = project(segments[kept.id(k)], p);
            if (x.distance2 < best.distance2) {
                best = {static_cast<int32_t>(kept.id(k)), x.distance2};
                projection = x;
            }
        }
        return best;
    }
    const SegmentBatch::Measured measured = kept.measureFrom(p, begin, end);
    const uint32_t nearest = kept.id(kept.nearest(begin, end, measured, [&](uint32_t k) {
        return project(segments[kept.id(k)], p).distance2;
    }));
    projection = project(segments[nearest], p);
    return {static_cast<int32_t>(nearest), projection.distance2};
}

/// A quarter's kept segments are measured in lanes from this many; one or two its points
/// measure themselves (on the 10k-segment tree both ways cost the same to 0.1 %).
constexpr uint32_t kQuarterLanesFrom = 3;

/// Fills BranchBuffers' quarter groups from the chunk's split.
void groupByQuarter(const PointQuarters& quarters, std::span<const Vec3> points,
                    BranchBuffers& buffers) {
    buffers.quarterCount.fill(0);
    for (size_t i = 0; i < points.size(); ++i) {
        const uint8_t q = quarters.quarterOf(i);
        const size_t place = buffers.quarterCount[q]++;
        buffers.placeInQuarter[i] = static_cast<uint8_t>(place);
        PointLanes& lanes = buffers.quarterPoints[q];
        lanes.x[place] = points[i].x;
        lanes.y[place] = points[i].y;
        lanes.z[place] = points[i].z;
    }
    for (int q = 0; q < 4; ++q) buffers.quarterPoints[q].pad(buffers.quarterCount[q]);
}

/// The first steps of the branch pass, chain by chain over the whole chunk in vectorised
/// loops: the cheap tests (reachTests) and, where a chain keeps at most kDirectScan segments
/// for the whole chunk or for a quarter of it, each point's nearest of them, and with
/// `plain` thickening the rest of each point's tests, its path and term (branchLanes).
void measureChains(const ReachBounds& bounds, bool plain, TileChains& chains,
                   const PointQuarters& quarters, std::span<const Vec3> points,
                   std::span<const GrowthSample> out, BranchBuffers& buffers) {
    const size_t n = points.size(), chainCount = chains.chains.size();
    buffers.points.fill(points);
    for (size_t i = 0; i < n; ++i) buffers.trunkTimes[i] = out[i].trunkTime;
    if (buffers.reach.size() < chainCount) buffers.reach.resize(chainCount);
    buffers.byQuarter.assign(chainCount, 0);
    buffers.nearestOf.assign(chainCount, {-1, -1, -1, -1});
    size_t used = 0;
    bool grouped = false;
    // Each point's nearest of the segments [begin, end) of the kept ones, into new lanes;
    // for the whole chunk's points (`whole`) with plain thickening, chain c's term there.
    auto measure = [&](size_t c, uint32_t begin, uint32_t end, const PointLanes& at, size_t count,
                       bool whole) {
        if (buffers.nearest.size() <= used) buffers.nearest.resize(used + 1);
        if (buffers.paths.size() <= used) buffers.paths.resize(used + 1);
        const std::span<const uint32_t> ids = chains.segments.ids(begin, end);
        nearestOfSegments(bounds.segments, ids, at, count, buffers.nearest[used]);
        if (plain && whole)
            branchLanes(bounds,
                        {ids, at, count, buffers.nearest[used], buffers.trunkTimes.data(),
                         buffers.reach[c]},
                        buffers.paths[used]);
        return static_cast<int32_t>(used++);
    };
    auto fewEnough = [](uint32_t begin, uint32_t end) {
        return end > begin && end - begin <= kDirectScan;
    };
    for (size_t c = 0; c < chainCount; ++c) {
        const TileChain& tc = chains.chains[c];
        reachTests(tc, bounds, buffers.points, n, buffers.trunkTimes.data(), buffers.reach[c]);
        auto same = [](const std::array<uint32_t, 4>& a) {
            return std::all_of(a.begin(), a.end(), [&](uint32_t x) { return x == a[0]; });
        };
        if (same(tc.begin) && same(tc.end)) {
            if (!fewEnough(tc.begin[0], tc.end[0])) continue;
            buffers.nearestOf[c].fill(measure(c, tc.begin[0], tc.end[0], buffers.points, n, true));
            continue;
        }
        // Split by quarter (so the chunk's quarters are known).
        for (int q = 0; q < 4; ++q) {
            if (!fewEnough(tc.begin[q], tc.end[q]) || tc.end[q] - tc.begin[q] < kQuarterLanesFrom)
                continue;
            if (!grouped) groupByQuarter(quarters, points, buffers), grouped = true;
            if (buffers.quarterCount[q] == 0) continue;
            buffers.nearestOf[c][q] = measure(c, tc.begin[q], tc.end[q], buffers.quarterPoints[q],
                                              buffers.quarterCount[q], false);
        }
        buffers.byQuarter[c] = 1;
    }
    // (Now that `paths` has stopped growing.)
    buffers.taken.assign(chainCount, {});
    for (size_t c = 0; c < chainCount && plain; ++c) {
        const int32_t index = buffers.nearestOf[c][0];
        if (index >= 0 && !buffers.byQuarter[c])
            buffers.taken[c] = {&buffers.paths[static_cast<size_t>(index)],
                                &buffers.nearest[static_cast<size_t>(index)]};
    }
}

/// Point i's nearest kept segment of chain c if measureChains measured it (its projection
/// in `projection`), else a Best without a segment.
Best measuredNearest(const BranchBuffers& buffers, const SegmentBatch& kept, const TileChain& tc,
                     size_t c, size_t i, uint8_t quarter, SegmentProjection& projection) {
    const int32_t index = buffers.nearestOf[c][quarter];
    if (index < 0) return {};
    const NearestLanes& lanes = buffers.nearest[static_cast<size_t>(index)];
    const size_t lane = buffers.byQuarter[c] ? buffers.placeInQuarter[i] : i;
    const uint32_t k = tc.begin[quarter] + static_cast<uint32_t>(lanes.which[lane]);
    projection = {lanes.tRaw[lane], lanes.t[lane], lanes.distance2[lane]};
    return {static_cast<int32_t>(kept.id(k)), lanes.distance2[lane]};
}

/// A chain's path that may come in under reach x T1 sin(alpha) at a point.
struct BranchCandidate {
    double sinAlpha;
    Best nearest;                  ///< the chain's nearest kept segment
    SegmentProjection projection;  ///< P's onto it
};

/// The tests of a chain at point p (trunk time t1) after reachTests passed it, given its
/// nearest kept segment, before its path time: false if its path cannot come in under
/// reach x T1 sin(alpha) there (weight 0), else the candidate.
bool mayComeUnderReach(const ReachBounds& r, const Best& best, const SegmentProjection& projection,
                       double t1, double sinAlpha, double radius2, BranchCandidate& out) {
    if (best.distance2 > radius2) return false;
    out = {sinAlpha, best, projection};
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
                                   BranchBuffers& buffers) const {
    if (chains.chains.empty()) return;
    const ReachBounds bounds{segments_, speedBound_, params_.age.delta, params_.junction.reach};
    const size_t n = points.size(), chainCount = chains.chains.size();
    measureChains(bounds, plainThickening_, chains, quarters, points, out, buffers);
    SegmentBatch& kept = chains.segments;
    std::vector<BranchTerm>& terms = buffers.terms;
    // (The buffers' arrays as local pointers: the terms' stores could alias the vectors.)
    const ReachLanes* const reach = buffers.reach.data();
    const TileChain* const tileChains = chains.chains.data();
    const BranchBuffers::TakenLanes* const taken = buffers.taken.data();
    for (size_t i = 0; i < n; ++i) {
        const Vec3& p = points[i];
        GrowthSample& g = out[i];
        const double t1 = g.trunkTime;
        terms.clear();
        const uint8_t quarter = quarters.quarterOf(i);
        for (size_t c = 0; c < chainCount; ++c) {
            const ReachLanes& lanes = reach[c];
            const TileChain& tc = tileChains[c];
            if (taken[c].terms) {
                // measureChains has taken the chain at this point in lanes.
                const size_t lane = i;
                const BranchLanes& at = *taken[c].terms;
                const auto state = static_cast<LaneState>(at.state[lane]);
                if (state == LaneState::kNone) continue;
                if (state != LaneState::kScalar) {
                    const NearestLanes& nearest = *taken[c].nearest;
                    const uint32_t segment =
                        kept.id(tc.begin[quarter] + static_cast<uint32_t>(nearest.which[lane]));
                    const FieldSegment& s = segments_[segment];
                    const double sinAlpha = lanes.sinAlpha[i];
                    double T = at.T[lane], weight = at.weight[lane];
                    if (state == LaneState::kDieback) {
                        T = dieback(T, s.deathTime, s.diebackExponent);
                        weight = junctionReachWeight(T / sinAlpha, t1, bounds.reach);
                        if (weight <= 0) continue;
                    }
                    terms.push_back({tc.chain,
                                     T,
                                     sinAlpha,
                                     at.distance[lane],
                                     at.dead[lane],
                                     weight,
                                     segment,
                                     {at.ax[lane], at.ay[lane], at.az[lane]},
                                     s.axis,
                                     at.Ta[lane],
                                     at.Tb[lane]});
                    continue;
                }
            }
            if (!lanes.passes(i)) continue;
            SegmentProjection projection{};
            Best best = measuredNearest(buffers, kept, tc, c, i, quarter, projection);
            if (best.segment == kNone)
                best = nearestKeptSegment(segments_, kept, tc.begin[quarter], tc.end[quarter], p,
                                          projection);
            BranchCandidate cand;
            if (!mayComeUnderReach(bounds, best, projection, t1, lanes.sinAlpha[i],
                                   lanes.radius2[i], cand))
                continue;
            const uint32_t segment = static_cast<uint32_t>(cand.nearest.segment);
            const PathTime path = chainPathTime(segment, p, cand.projection);
            const double weight = junctionReachWeight(path.T / cand.sinAlpha, t1, bounds.reach);
            if (weight <= 0) continue;
            // A dead knot: the branch had died before the trunk's bark reached P, so P lies in
            // the dead stub that the trunk encased.
            // The change from intergrown to encased knot is sharp in real wood; one year of
            // trunk growth keeps it from aliasing.
            const double deathTime = segments_[segment].deathTime;
            const double dead =
                std::isfinite(deathTime) ? smoothstep(deathTime - 0.5, deathTime + 0.5, t1) : 0.0;
            terms.push_back({tc.chain, path.T, cand.sinAlpha, path.distance, dead, weight, segment,
                             path.axisPoint, path.axisDirection, path.Ta, path.Tb});
        }
        if (terms.empty()) continue;
        if (const BranchTerm* top = blendJunction(terms, params_.junction.p, g))
            describeKnot(*top, p, t1, g);
    }
}

inline void GrowthField::describeKnot(const BranchTerm& t, const Vec3& point, double trunkTime,
                                      GrowthSample& g) const {
    g.knotChain = static_cast<int32_t>(t.chain);
    g.knotAxisDistance = t.distance;
    g.knotOffset = point - t.axisPoint;
    g.knotAxisDirection = t.axisDirection;
    // The knot's edge: the branch's share is one half where w (m / x)^p = (m / T1)^p with
    // x = Tc / sin(alpha), i.e. Tc = T1 sin(alpha) w^(1/p); past the branch's death that time
    // is a dieback'd one, so undo eq. 10 to get back to the time the growth terms give.
    const FieldSegment& s = segments_[t.segment];
    // (w^(1/p) is exactly 1 for w = 1, the usual weight, and a square root for the usual p.)
    const double p = params_.junction.p;
    const double root = t.weight == 1 ? 1.0
                        : p == 2      ? std::sqrt(t.weight)
                                      : std::pow(t.weight, 1 / p);
    double edge = trunkTime * t.sinAlpha * root;
    if (edge > s.deathTime)
        edge = s.deathTime * std::pow(edge / s.deathTime, 1 / (1 + s.diebackExponent));
    g.knotDied = t.dead > 0.5;
    g.knotRadius = radiusAtTime(t.segment, t.Ta, t.Tb, t.distance, edge);
}

}  // namespace nenrin
