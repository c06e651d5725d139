/// The growth field's trunk pass: every point's trunk path time T1 (docs/model.md, "How
/// evaluation is organised", step 2).

#include <algorithm>
#include <cmath>
#include <utility>

#include "grain/field_bounds.h"
#include "grain/field_passes.h"
#include "grain/growth_field.h"
#include "grain/path_time.h"
#include "grain/segment_lanes.h"

namespace nenrin {

namespace {

/// The batch's trunk candidates (sorted) that can be the nearest of some point of the chunk,
/// in `kept`: a point's nearest lies within the chunk centre's nearest distance plus twice
/// the half-diagonal (sorted order is kept, so ties still go to the smaller id).
std::span<const uint32_t> keepTrunkCandidates(std::span<const FieldSegment> segments,
                                              std::span<const uint32_t> candidates,
                                              const PointBox& chunk, std::vector<double>& dist,
                                              std::vector<uint32_t>& kept) {
    const Vec3 cc = chunk.centre();
    const double ch = chunk.halfDiagonal();
    dist.clear();
    double nearest = kInf;
    for (uint32_t id : candidates) {
        dist.push_back(std::sqrt(project(segments[id], cc).distance2));
        nearest = std::min(nearest, dist.back());
    }
    kept.clear();
    for (size_t k = 0; k < candidates.size(); ++k)
        if (dist[k] <= nearest + 2 * ch + 1e-9) kept.push_back(candidates[k]);
    return kept;
}

/// True if every point of the box projects strictly inside the segment's slab and lies past
/// the previous segment's end and before the next one's start (so the neighbours' nearest
/// points are the shared joints, and eq. 4 needs no blend).
bool insideSlabOnly(std::span<const FieldSegment> segments, uint32_t segmentId,
                    const PointBox& box) {
    // tRaw is linear in P, so over the box it spans the range of its corner values.
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
    const FieldSegment& s = segments[segmentId];
    auto [mn, mx] = range(s);
    if (mn < kMargin || mx > 1 - kMargin) return false;
    // Past the previous segment's end and before the next one's start: on this segment's
    // side of both joints, where the joint is the neighbour's nearest point.
    if (s.previous != kNone && !(range(segments[s.previous]).first > 1 + kMargin)) return false;
    if (s.next != kNone && !(range(segments[s.next]).second < -kMargin)) return false;
    return true;
}

/// The fast path: the kept candidate whose path every point of the chunk takes without a
/// joint blend, or kNone. That is one inside whose slab and outside whose neighbours' the
/// chunk lies (with a margin for rounding), the other candidates being those neighbours:
/// chainPathTime would take the no-blend branch for every point. Chain neighbours cannot win
/// then either: P projects strictly inside the segment, so it is strictly nearer to it than
/// to their joint with it.
int32_t plainSegment(std::span<const FieldSegment> segments, std::span<const uint32_t> kept,
                     const PointBox& chunk) {
    for (uint32_t id : kept) {
        const FieldSegment& x = segments[id];
        bool onlyNeighbours = std::all_of(kept.begin(), kept.end(), [&](uint32_t k) {
            return k == id || static_cast<int32_t>(k) == x.previous ||
                   static_cast<int32_t>(k) == x.next;
        });
        if (onlyNeighbours && insideSlabOnly(segments, id, chunk)) return static_cast<int32_t>(id);
    }
    return kNone;
}

/// The segment of `kept` that is every one of the first n points' nearest, or kNone.
int32_t commonNearest(const NearestLanes& nearest, size_t n, std::span<const uint32_t> kept) {
    for (size_t k = 1; k < n; ++k)
        if (nearest.which[k] != nearest.which[0]) return kNone;
    return n > 0 ? static_cast<int32_t>(kept[static_cast<size_t>(nearest.which[0])]) : kNone;
}

/// A sample with its trunk path and nothing else, written in place field by field (a
/// GrowthSample is 22 words: made and then copied, it cost twice the stores; cleared first,
/// GCC cleared it with `rep stos`, whose start-up cost more than the stores themselves:
/// BM_GrowthField/10000/1 2.65 -> 2.46 ms).
static_assert(sizeof(GrowthSample) == 176, "a new GrowthSample field: set it in setTrunkSample");
void setTrunkSample(GrowthSample& g, const GrowthField::PathTime& trunk) {
    g.T = g.trunkTime = trunk.T;
    g.Ta = trunk.Ta;
    g.Tb = trunk.Tb;
    g.axisPoint = trunk.axisPoint;
    g.axisDirection = trunk.axisDirection;
    g.knot = g.deadKnot = 0;
    g.knotChain = -1;
    g.knotAxisDistance = g.knotRadius = 0;
    g.knotDied = false;
    g.knotOffset = g.knotAxisDirection = Vec3{};
}

}  // namespace

double GrowthField::evaluateTrunk(std::span<const Vec3> points, const PointBox& batch,
                                  std::span<const PointBox> chunks, std::span<GrowthSample> out,
                                  TrunkBuffers& buffers) const {
    // Every point of the batch is within d0 + h of some trunk segment, so its nearest trunk
    // segment is within d0 + 2h of the centre.
    const Vec3 centre = batch.centre();
    NearestSegment near = index_->trunk().nearest(centre);
    std::vector<uint32_t>& candidates = buffers.candidates;
    candidates.clear();
    index_->trunk().gather(centre, std::sqrt(near.distance2) + 2 * batch.halfDiagonal() + 1e-9,
                           candidates);
    std::sort(candidates.begin(), candidates.end());

    std::vector<double>& chunkMaxima = buffers.chunkMaxima;
    chunkMaxima.assign(chunks.size(), 0.0);
    for (size_t c0 = 0; c0 < points.size(); c0 += kChunk) {
        const size_t c1 = std::min(points.size(), c0 + kChunk);
        double& maxTrunkTime = chunkMaxima[c0 / kChunk];
        const PointBox& chunk = chunks[c0 / kChunk];
        const std::span<const uint32_t> kept = keepTrunkCandidates(
            segments_, candidates, chunk, buffers.centreDistances, buffers.kept);
        const std::span<const Vec3> chunkPoints = points.subspan(c0, c1 - c0);
        NearestLanes& nearest = buffers.nearest;
        int32_t plain = plainSegment(segments_, kept, chunk);
        if (plain == kNone) {
            // Each point's nearest kept segment, found for all of them at once. Far from the
            // axis the distance bound keeps segments beyond the neighbours; if every point's
            // nearest is the same one and the chunk lies in its slab alone, the chunk is plain.
            buffers.points.fill(chunkPoints);
            nearestOfSegments(segments_, kept, buffers.points, chunkPoints.size(), nearest);
            const int32_t common = commonNearest(nearest, chunkPoints.size(), kept);
            if (common != kNone && insideSlabOnly(segments_, static_cast<uint32_t>(common), chunk))
                plain = common;
        }
        if (plain != kNone) {
            // One segment's path for every point: its geometry in one vectorised loop.
            const FieldSegment& s = segments_[static_cast<uint32_t>(plain)];
            SegmentLanes& lanes = buffers.lanes;
            measureInsideSegment(s, chunkPoints, lanes);
            for (size_t i = c0, k = 0; i < c1; ++i, ++k) {
                const Vec3 axisPoint{lanes.ax[k], lanes.ay[k], lanes.az[k]};
                const double Ta = lanes.Ta[k], distance = lanes.distance[k];
                const double Tb = plainThickening_ ? distance * s.inverseSpeed
                                                   : thickening(static_cast<uint32_t>(plain), Ta,
                                                                points[i] - axisPoint, distance);
                setTrunkSample(out[i], {Ta + Tb, Ta, Tb, axisPoint, s.axis, distance});
                maxTrunkTime = std::max(maxTrunkTime, out[i].T);
            }
            continue;
        }
        for (size_t i = c0, k = 0; i < c1; ++i, ++k) {
            const uint32_t id = kept[static_cast<size_t>(nearest.which[k])];
            setTrunkSample(out[i],
                           chainPathTime(id, points[i],
                                         {nearest.tRaw[k], nearest.t[k], nearest.distance2[k]}));
            maxTrunkTime = std::max(maxTrunkTime, out[i].T);
        }
    }
    double maxTrunkTime = 0;
    for (const double t : chunkMaxima) maxTrunkTime = std::max(maxTrunkTime, t);
    return maxTrunkTime;
}

}  // namespace nenrin
