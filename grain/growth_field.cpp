#include "grain/growth_field.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "grain/field_bounds.h"
#include "grain/field_rings.h"
#include "grain/growth_terms.h"
#include "skeleton/segment_geometry.h"

namespace nenrin {

namespace {

/// Points per chunk: the unit of candidate pruning inside a batch (an 8 x 8 tile).
constexpr size_t kChunk = 64;
/// Points per group of chunks: branch chains are culled for each before its chunks, when the
/// tile has more candidate chains than kGroupCullAbove (with few, the culls cost more than
/// they save).
constexpr size_t kGroup = 4 * kChunk;
constexpr size_t kGroupCullAbove = 64;
/// Up to this many kept segments of a chain, a point measures them in double one by one: the
/// vectorised float pass only pays beyond.
constexpr uint32_t kDirectScan = 12;

/// The nearest segment found so far. Candidates are visited in id order and only a strictly
/// smaller distance replaces it, so ties go to the smaller id, like the indexes.
struct Best {
    int32_t segment = kNone;
    double distance2 = kInf;
};

}  // namespace

GrowthField::GrowthField(const SkeletonIndex& index, const GrainParams& params)
    : index_(&index), params_(params) {
    if (index.skeleton().empty() || index.trunk().size() == 0)
        throw std::invalid_argument("GrowthField: the skeleton has no trunk");
    sway_ = makeSwayWaves(params_.sway);
    segments_ = flattenSegments(index.skeleton());
    for (FieldSegment& f : segments_) f.inverseSpeed = 1 / (params_.radialSpeed * f.gamma);
    const Skeleton& sk = index.skeleton();
    chainTrees_ = ChainTrees(segments_, sk.chains(), index.backend() != IndexBackend::BruteForce);
    for (const SkeletonChain& c : sk.chains()) {
        const FieldSegment& first = segments_[c.firstSegment];
        ChainFrame f{first.a, first.axis, kInf, 0, 0, kInf};
        for (uint32_t i = c.firstSegment; i < c.firstSegment + c.segmentCount; ++i) {
            f.birthBound = std::min(f.birthBound, segments_[i].birthBound);
            f.gammaBound = std::max(f.gammaBound, segments_[i].gammaBound);
            f.deathBound = std::max(f.deathBound, segments_[i].deathBound);
            f.diebackBound = std::min(f.diebackBound, segments_[i].diebackBound);
        }
        chainFrames_.push_back(f);
    }
    maxGamma_ = index.skeleton().maxBranchGamma();
    // Largest radial speed any path can have (taper x direction x jitter): distance bounds.
    speedBound_ = params_.radialSpeed * (1 + params_.taper.nu) * (1 + params_.direction.strength) /
                  (1 - params_.sway.radialJitter);
    const FieldRings rings = fieldRingWidths(sk, params_);
    latewoodTiming_ = fieldLatewoodTiming(sk, rings, lateWoodShape(params_.colour));
    if (!rings.widths.empty()) {
        radialGrowth_ = RadialGrowth(rings.widths, params_.radialSpeed);
        // Years faster than Sb shorten thickening times by up to this ratio; the distance
        // bounds pass their years through the age warp, hence the 1/delta power.
        speedBound_ *= std::pow(radialGrowth_.maxSpeedRatio(), 1 / params_.age.delta);
    }
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
    // Eq. 3/3': Tb = Db / S with S = Sb gamma (x taper, x direction).
    double db = r.distance;
    double speedFactor = taperFactor(r.Ta, params_.taper.nu, params_.taper.omega);
    // The outward normal only matters to the direction term and the radial jitter.
    if (params_.direction.strength != 0 || sway_.radialJitter != 0) {
        Vec3 n = r.distance > 0 ? d * (1 / r.distance) : Vec3{};
        speedFactor *= directionFactor(n, params_.direction.sunRay, params_.direction.strength);
        if (sway_.radialJitter != 0) db *= swayRadialFactor(n, s.axis, r.Ta, sway_);
    }
    r.Tb = ageWarp(thickeningTime(db, s.inverseSpeed, speedFactor), params_.age.delta);
    if (!radialGrowth_.empty()) r.Tb = radialGrowth_.arrivalTime(r.Ta, r.Tb) - r.Ta;
    r.T = r.Ta + r.Tb;
    if (s.branch) r.T = dieback(r.T, s.deathTime, s.diebackExponent);
    return r;
}

GrowthField::PathTime GrowthField::chainPathTime(uint32_t segmentId, const Vec3& p) const {
    const FieldSegment& s = segments_[segmentId];
    SegmentProjection proj = project(s, p);
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

void GrowthField::describeKnot(const GrowthScratch::ChainTerm& t, const Vec3& point,
                               double trunkTime, GrowthSample& g) const {
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

bool GrowthField::insideSlabOnly(uint32_t segmentId, const Vec3& lo, const Vec3& hi) const {
    // tRaw is linear in P, so over the box it spans the range of its corner values.
    const PointBox box{lo, hi};
    auto range = [&](const FieldSegment& x) {
        double mn = kInf, mx = -kInf;
        for (int corner = 0; corner < 8; ++corner) {
            double t = dot(box.corner(corner) - x.a, x.ab) * x.invLength2;
            mn = std::min(mn, t);
            mx = std::max(mx, t);
        }
        return std::pair{mn, mx};
    };
    constexpr double kMargin = 1e-6;
    const FieldSegment& s = segments_[segmentId];
    auto [mn, mx] = range(s);
    if (mn < kMargin || mx > 1 - kMargin) return false;
    // Past the previous segment's end and before the next one's start: on this segment's
    // side of both joints, where the joint is the neighbour's nearest point.
    if (s.previous != kNone && !(range(segments_[s.previous]).first > 1 + kMargin)) return false;
    if (s.next != kNone && !(range(segments_[s.next]).second < -kMargin)) return false;
    return true;
}

GrowthSample GrowthField::evaluate(const Vec3& p) const {
    GrowthScratch scratch;
    GrowthSample out;
    evaluateBatch({&p, 1}, {&out, 1}, scratch);
    return out;
}

void GrowthField::evaluateBatch(std::span<const Vec3> input, std::span<GrowthSample> out,
                                GrowthScratch& scratch, size_t stencil) const {
    // One gather from the index for the whole batch; then, chunk by chunk (consecutive runs of
    // kChunk points, which callers keep spatially compact), exact pruning to what can matter
    // for that chunk, and the per-point work.
    const size_t n = input.size();
    if (n == 0) return;
    // The field's domain: beyond it squared distances overflow and no segment would be nearest
    // (once a crash). Farther points are evaluated as if on its edge, where the answer is long
    // settled (bark or beyond); NaN has no answer. Callers bound their inputs where they read
    // them; this keeps a missed case harmless.
    auto inDomain = [](const Vec3& p) {
        if (std::isnan(p.x) || std::isnan(p.y) || std::isnan(p.z))
            throw std::domain_error("growth field: a point with a NaN coordinate");
        if (std::abs(p.x) <= kFieldDomain && std::abs(p.y) <= kFieldDomain &&
            std::abs(p.z) <= kFieldDomain)
            return p;
        return Vec3{std::clamp(p.x, -kFieldDomain, kFieldDomain),
                    std::clamp(p.y, -kFieldDomain, kFieldDomain),
                    std::clamp(p.z, -kFieldDomain, kFieldDomain)};
    };
    auto& pts = scratch.points;
    pts.resize(n);
    if (stencil <= 1 || n % stencil != 0) {
        for (size_t i = 0; i < n; ++i) {
            const Vec3 p = inDomain(input[i]);
            pts[i] = p + swayDisplacement(p, sway_);
        }
    } else {
        for (size_t i = 0; i < n; i += stencil) {
            const Vec3 d = swayDisplacement(inDomain(input[i]), sway_);
            for (size_t j = i; j < i + stencil; ++j) pts[j] = inDomain(input[j]) + d;
        }
    }
    const PointBox batch = boxOf(pts);
    const Vec3 centre = batch.centre();
    const double halfDiagonal = batch.halfDiagonal();

    // Trunk: every point of the batch is within d0 + h of some trunk segment, so its nearest
    // trunk segment is within d0 + 2h of the centre.
    NearestSegment near = index_->trunk().nearest(centre);
    auto& trunkCands = scratch.trunkCandidates;
    trunkCands.clear();
    index_->trunk().gather(centre, std::sqrt(near.distance2) + 2 * halfDiagonal + 1e-9, trunkCands);
    std::sort(trunkCands.begin(), trunkCands.end());

    double maxTrunkTime = 0;
    for (size_t c0 = 0; c0 < n; c0 += kChunk) {
        const size_t c1 = std::min(n, c0 + kChunk);
        const PointBox chunk = boxOf({pts.data() + c0, c1 - c0});
        // The same argument per chunk: keep the trunk candidates that can be some point's
        // nearest (sorted order is kept, so ties still go to the smaller id).
        const Vec3 cc = chunk.centre();
        const double ch = chunk.halfDiagonal();
        auto& dist = scratch.centreDistances;
        dist.clear();
        double nearest = kInf;
        for (uint32_t id : trunkCands) {
            dist.push_back(std::sqrt(project(segments_[id], cc).distance2));
            nearest = std::min(nearest, dist.back());
        }
        auto& kept = scratch.chunkTrunk;
        kept.clear();
        for (size_t k = 0; k < trunkCands.size(); ++k)
            if (dist[k] <= nearest + 2 * ch + 1e-9) kept.push_back(trunkCands[k]);
        // Fast path: the chunk lies inside one candidate's slab and outside its neighbours'
        // (with a margin for rounding), and the other candidates are those neighbours:
        // chainPathTime would take the no-blend branch for every point, so call what it would.
        // Chain neighbours cannot win then either: P projects strictly inside the segment, so
        // it is strictly nearer to it than to their joint with it.
        int32_t plain = kNone;
        for (uint32_t id : kept) {
            const FieldSegment& x = segments_[id];
            bool onlyNeighbours = std::all_of(kept.begin(), kept.end(), [&](uint32_t k) {
                return k == id || static_cast<int32_t>(k) == x.previous ||
                       static_cast<int32_t>(k) == x.next;
            });
            if (onlyNeighbours && insideSlabOnly(id, chunk.lo, chunk.hi)) {
                plain = static_cast<int32_t>(id);
                break;
            }
        }
        for (size_t i = c0; i < c1; ++i) {
            const Vec3& p = pts[i];
            PathTime trunk;
            if (plain != kNone) {
                uint32_t id = static_cast<uint32_t>(plain);
                trunk = segmentPathTime(id, p, project(segments_[id], p).tRaw);
            } else {
                Best best;
                for (uint32_t id : kept) {
                    double d2 = project(segments_[id], p).distance2;
                    if (d2 < best.distance2) best = {static_cast<int32_t>(id), d2};
                }
                trunk = chainPathTime(static_cast<uint32_t>(best.segment), p);
            }
            GrowthSample& g = out[i];
            g = GrowthSample{};
            g.T = g.trunkTime = trunk.T;
            g.Ta = trunk.Ta;
            g.Tb = trunk.Tb;
            g.axisPoint = trunk.axisPoint;
            g.axisDirection = trunk.axisDirection;
            maxTrunkTime = std::max(maxTrunkTime, trunk.T);
        }
    }
    if (index_->branches().size() == 0) return;

    // The chains with a segment near the batch, in chain order: each is then searched
    // through its own hierarchy, however finely it is divided.
    auto& chains = scratch.candidateChains;
    chains.clear();
    index_->branchChains().gather(centre, branchSearchRadius(maxTrunkTime) + halfDiagonal + 1e-9,
                                  chains);
    if (chains.empty()) return;
    std::sort(chains.begin(), chains.end());
    chains.erase(std::unique(chains.begin(), chains.end()), chains.end());
    // Tests 1-3 of prepareTileChains once for the whole batch, then per group of chunks
    // (whose trunk times vary less than the batch's), each over a ball that holds every
    // chunk's in it (twice the half-diagonal: a chunk's centre lies within one of the
    // group's, its half-diagonal is at most the group's): what fails there fails for every
    // chunk.
    auto largestTrunkTime = [&](size_t i0, size_t i1) {
        double t = 0;
        for (size_t i = i0; i < i1; ++i) t = std::max(t, out[i].trunkTime);
        return t;
    };
    auto mayMatterInside = [&](uint32_t chain, const PointBox& box, double trunkTime) {
        ChainReach reach;
        return chainMayMatter(chain, box.lo, box.hi, box.centre(), 2 * box.halfDiagonal(),
                              trunkTime, reach);
    };
    std::erase_if(chains,
                  [&](uint32_t chain) { return !mayMatterInside(chain, batch, maxTrunkTime); });
    for (size_t g0 = 0; g0 < n; g0 += kGroup) {
        const size_t g1 = std::min(n, g0 + kGroup);
        std::span<const uint32_t> groupChains = chains;
        if (n > kGroup && chains.size() > kGroupCullAbove) {
            const PointBox group = boxOf({pts.data() + g0, g1 - g0});
            const double groupTrunkTime = largestTrunkTime(g0, g1);
            auto& culled = scratch.groupChains;
            culled.clear();
            for (const uint32_t chain : chains)
                if (mayMatterInside(chain, group, groupTrunkTime)) culled.push_back(chain);
            groupChains = culled;
        }
        for (size_t c0 = g0; c0 < g1; c0 += kChunk) {
            const size_t c1 = std::min(g1, c0 + kChunk);
            const std::span<const Vec3> chunkPoints{pts.data() + c0, c1 - c0};
            const PointBox chunk = boxOf(chunkPoints);
            scratch.quarters.reset(chunkPoints, chunk.lo, chunk.hi);
            prepareTileChains(scratch, groupChains, chunk.lo, chunk.hi, chunk.halfDiagonal(),
                              largestTrunkTime(c0, c1));
            evaluateBranches(chunkPoints, out.subspan(c0, c1 - c0), scratch);
        }
    }
}

void GrowthField::evaluateBranches(std::span<const Vec3> pts, std::span<GrowthSample> out,
                                   GrowthScratch& scratch) const {
    const size_t n = pts.size();
    const double p = params_.junction.p;
    const double reach = params_.junction.reach;
    for (size_t i = 0; i < n; ++i) {
        const Vec3& pt = pts[i];
        GrowthSample& g = out[i];
        const double t1 = g.trunkTime;
        auto& terms = scratch.terms;
        terms.clear();
        if (scratch.tileChains.empty()) continue;
        const uint8_t quarter = scratch.quarters.quarterOf(i);
        for (const auto& tc : scratch.tileChains) {
            // alpha: angle between QP and the plane F through the branch start Q,
            // perpendicular to the branch (eq. 5). Behind F the branch does not count.
            Vec3 v = pt - tc.start;
            double lv = length(v);
            double sinAlpha = lv > 0 ? dot(v, tc.direction) / lv : 0;
            if (sinAlpha <= 0) continue;
            // Beyond this distance T_c / sin(alpha) is past reach x T1: weight 0.
            double slack = reach * t1 * sinAlpha - tc.birthBound;
            if (slack <= 0) continue;
            double radius = tc.gamma * speedBound_ * ageUnwarp(slack, params_.age.delta);
            double radius2 = radius * radius;
            // Quick reject: the box around the chain's kept segments is out of reach.
            Vec3 out{std::max(std::max(tc.lower.x - pt.x, pt.x - tc.upper.x), 0.0),
                     std::max(std::max(tc.lower.y - pt.y, pt.y - tc.upper.y), 0.0),
                     std::max(std::max(tc.lower.z - pt.z, pt.z - tc.upper.z), 0.0)};
            if (dot(out, out) > radius2) continue;
            // The nearest kept segment: a few (the usual case) measured in double directly, more
            // in one vectorised float pass with near-ties settled in double. Both give the
            // smallest double distance, ties to the first (smaller id).
            auto& kept = scratch.keptSegments;
            Best best;
            const uint32_t begin = tc.begin[quarter], end = tc.end[quarter];
            if (end - begin <= kDirectScan) {
                for (uint32_t k = begin; k < end; ++k) {
                    const double d2 = project(segments_[kept.id(k)], pt).distance2;
                    if (d2 < best.distance2) best = {static_cast<int32_t>(kept.id(k)), d2};
                }
            } else {
                const SegmentBatch::Measured measured = kept.measureFrom(pt, begin, end);
                const uint32_t nearest =
                    kept.id(kept.nearest(begin, end, measured, [&](uint32_t k) {
                        return project(segments_[kept.id(k)], pt).distance2;
                    }));
                best = {static_cast<int32_t>(nearest), project(segments_[nearest], pt).distance2};
            }
            if (best.distance2 > radius2) continue;
            // The path through the nearest segment cannot come in under reach x T1: skip it
            // before paying for the full path time.
            const FieldSegment& bs = segments_[static_cast<uint32_t>(best.segment)];
            const double needed = reach * t1 * sinAlpha;
            if (bs.birthBound >= needed) continue;
            if (std::isfinite(bs.deathBound)) {
                double bound = bs.birthBound +
                               ageWarp(std::sqrt(best.distance2) / (bs.gammaBound * speedBound_),
                                       params_.age.delta);
                if (diebackLowerBound(bound, bs.deathBound, bs.diebackBound) >= needed) continue;
            } else {  // the same bound for a living branch, as a distance: no square root
                double reachable = bs.gammaBound * speedBound_ *
                                   ageUnwarp(needed - bs.birthBound, params_.age.delta);
                if (best.distance2 >= reachable * reachable) continue;
            }
            PathTime bp = chainPathTime(static_cast<uint32_t>(best.segment), pt);
            const double weight = junctionReachWeight(bp.T / sinAlpha, t1, reach);
            if (weight <= 0) continue;
            // A dead knot: the branch had died before the trunk's bark reached P, so P lies in
            // the dead stub that the trunk encased.
            // The change from intergrown to encased knot is sharp in real wood; one year of
            // trunk growth keeps it from aliasing.
            double deathTime = segments_[static_cast<uint32_t>(best.segment)].deathTime;
            double dead =
                std::isfinite(deathTime) ? smoothstep(deathTime - 0.5, deathTime + 0.5, t1) : 0.0;
            terms.push_back({tc.chain, bp.T, sinAlpha, bp.distance, dead, weight,
                             static_cast<uint32_t>(best.segment), bp.axisPoint, bp.axisDirection,
                             bp.Ta, bp.Tb});
        }
        if (terms.empty()) continue;

        // Eq. 5 over the trunk and every branch path.
        double m = t1;
        for (const auto& t : terms) m = std::min(m, t.time / t.sinAlpha);
        if (m <= 0) {
            g.T = 0;
            continue;
        }
        JunctionSum sum(m, t1, p);
        double dead = 0, strongest = 0;
        const GrowthScratch::ChainTerm* top = nullptr;
        for (const auto& t : terms) {
            double u = sum.add(t.time / t.sinAlpha, t.weight);
            dead += t.dead * u;
            if (u > strongest) strongest = u, top = &t;
        }
        g.T = sum.time();
        g.knot = sum.branchShare();
        g.deadKnot = dead / sum.sum();
        if (top) describeKnot(*top, pt, t1, g);
    }
}

}  // namespace nenrin
