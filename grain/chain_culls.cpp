/// The growth field's culls of branch chains: which chains can matter for a box of points,
/// and for a chunk, which of their segments each quarter of it must measure. Every test is a
/// bound over the whole box, so no answer depends on how points were batched.

#include <algorithm>
#include <cmath>

#include "grain/field_bounds.h"
#include "grain/field_passes.h"
#include "grain/growth_field.h"
#include "grain/growth_terms.h"

namespace nenrin {

namespace {

/// A chain meeting a chunk in more segments than this gets a narrower list per quarter: its
/// points then measure fewer each. With plain thickening a chain that keeps few enough
/// segments for the branch lanes (at most 12: grain/branch_lanes.h) takes them for the whole
/// chunk instead, which costs less per point than quarters measured point by point (on the
/// 100k-segment tree 47.4 -> 44.8 M instructions; the 10k tree's chains keep fewer anyway).
constexpr size_t kQuarterAbove = 3, kQuarterAbovePlain = 12;

}  // namespace

double GrowthField::branchSearchRadius(double trunkTime) const {
    // A branch path at distance D has T_c >= (D / (gamma speedBound))^delta; once that reaches
    // reach x T1 its weight is 0, so farther segments need not be looked at.
    return maxGamma_ * speedBound_ *
           ageUnwarp(params_.junction.reach * std::max(trunkTime, 0.0), params_.age.delta);
}

bool GrowthField::chainMayMatter(uint32_t chain, const PointBox& box, const Vec3& centre,
                                 double radius, double maxTrunkTime, ChainReach& out) const {
    const double reachTrunkTime = params_.junction.reach * maxTrunkTime;
    // 1. Born too late to come in under reach x T1 anywhere (sin(alpha) <= 1).
    const ChainFrame& frame = chainFrames_[chain];
    if (frame.birthBound >= reachTrunkTime) return false;
    // 2. The whole box behind the plane F of the branch: sin(alpha) <= 0 everywhere.
    bool anyAhead = false;
    for (int corner = 0; corner < 8 && !anyAhead; ++corner)
        anyAhead = dot(box.corner(corner) - frame.start, frame.direction) > 0;
    if (!anyAhead) return false;
    // The largest sin(alpha) over the ball, seen from Q: the blend compares T_c / sin(alpha)
    // with T1. With c the cosine of the angle between QC and the branch and s the sine of
    // the ball's half-angle, it is cos(angle - spread), or 1 once the ball reaches the
    // branch's axis.
    const Vec3 toCentre = centre - frame.start;
    const double dc = length(toCentre);
    double sinAlphaMax = 1;
    if (dc > radius) {
        const double c = std::clamp(dot(toCentre, frame.direction) / dc, -1.0, 1.0);
        const double s = std::min(1.0, radius / dc * (1 + 1e-9) + 1e-12);
        const double cosSpread = std::sqrt(std::max(0.0, 1 - s * s));
        if (c < cosSpread)
            sinAlphaMax = std::min(
                1.0,
                (c * cosSpread + std::sqrt(std::max(0.0, 1 - c * c)) * s) * (1 + 1e-12) + 1e-12);
    }
    out.reachTime = reachTrunkTime * sinAlphaMax;
    // 3. The chain's path time over the whole ball is past reach x T1 x sin(alpha) of every
    //    point: from births alone, then from the chain's distance to the ball (looked up only
    //    as far as it could matter); a dead branch's dieback (eq. 10) shortens that distance.
    const double budget = diebackBudget(out.reachTime, frame.deathBound, frame.diebackBound);
    if (frame.birthBound >= budget) return false;
    const double reachable =
        frame.gammaBound * speedBound_ * ageUnwarp(budget - frame.birthBound, params_.age.delta) +
        radius;
    const double limit = reachable * (1 + 1e-9) + 1e-9;
    out.nearest = chainTrees_.nearest(chain, centre, limit * limit);
    return out.nearest.segment != kNone;
}

bool GrowthField::chainMayMatterInside(uint32_t chain, const PointBox& box,
                                       double maxTrunkTime) const {
    ChainReach reach;
    return chainMayMatter(chain, box, box.centre(), 2 * box.halfDiagonal(), maxTrunkTime, reach);
}

void GrowthField::nearbyChains(const PointBox& batch, double maxTrunkTime,
                               std::vector<uint32_t>& chains) const {
    // The chains with a segment near the batch, in chain order: each is then searched
    // through its own hierarchy, however finely it is divided.
    chains.clear();
    index_->branchChains().gather(
        batch.centre(), branchSearchRadius(maxTrunkTime) + batch.halfDiagonal() + 1e-9, chains);
    std::sort(chains.begin(), chains.end());
    chains.erase(std::unique(chains.begin(), chains.end()), chains.end());
    // Tests 1-3 once for the whole batch: a chain that fails here is not tested again per
    // group or chunk.
    std::erase_if(
        chains, [&](uint32_t chain) { return !chainMayMatterInside(chain, batch, maxTrunkTime); });
}

std::span<const uint32_t> GrowthField::cullChains(std::span<const uint32_t> chains,
                                                  const PointBox& group, double maxTrunkTime,
                                                  std::vector<uint32_t>& kept) const {
    kept.clear();
    for (const uint32_t chain : chains)
        if (chainMayMatterInside(chain, group, maxTrunkTime)) kept.push_back(chain);
    return kept;
}

void GrowthField::prepareTileChains(std::span<const uint32_t> candidates, const PointBox& chunk,
                                    double maxTrunkTime, PointQuarters& quarters, TileChains& out,
                                    CullBuffers& buffers) const {
    // Keep the chains near the batch that can matter for some point of the tile; every test
    // here is exact (a bound over the whole box), so results do not depend on tiling.
    const Vec3 centre = chunk.centre();
    const double halfDiagonal = chunk.halfDiagonal();
    out.chains.clear();
    SegmentBatch& kept = out.segments;
    kept.reset(centre);
    for (const uint32_t chain : candidates) {
        // 1-3: births, plane F and distance, over the chunk's bounding ball.
        ChainReach reach;
        if (!chainMayMatter(chain, chunk, centre, halfDiagonal, maxTrunkTime, reach)) continue;
        const ChainFrame& frame = chainFrames_[chain];
        const double reachTime = reach.reachTime;
        const ChainTrees::Nearest& nearestToCentre = reach.nearest;
        const double nearest = std::sqrt(nearestToCentre.distance2);
        // 4. Segments that cannot be any point's nearest (on a straight run, all but the few
        //    the box projects onto).
        auto& ids = buffers.chainSegments;
        ids.clear();
        const double farthest = chainTrees_.candidates(
            chain, chunk.lo, chunk.hi, static_cast<uint32_t>(nearestToCentre.segment), ids);
        TileChain tc;
        tc.chain = chain;
        tc.start = frame.start;
        tc.direction = frame.direction;
        PointBox bounds;
        tc.gamma = 0;
        tc.birthBound = kInf;
        for (const uint32_t id : ids) {
            const FieldSegment& s = segments_[id];
            bounds.add(s.a);
            bounds.add(s.a + s.ab);
            tc.gamma = std::max(tc.gamma, s.gammaBound);
            tc.birthBound = std::min(tc.birthBound, s.birthBound);
        }
        tc.lower = bounds.lo;
        tc.upper = bounds.hi;
        const double closest = std::max(0.0, nearest - halfDiagonal) * (1 - 1e-9);
        if (ids.empty() ||
            tc.birthBound + ageWarp(closest / (tc.gamma * speedBound_), params_.age.delta) >=
                reachTime)
            continue;
        // 5. Per quarter of the chunk, the segments that can be nearest for its points (worth
        //    it once a chain meets the tile in more than a few).
        auto keep = [&](std::span<const uint32_t> segments) {
            for (const uint32_t id : segments)
                kept.push(segments_[id].a, segments_[id].ab, segments_[id].invLength2, id);
        };
        if (ids.size() <= (plainThickening_ ? kQuarterAbovePlain : kQuarterAbove)) {
            tc.begin.fill(kept.size());
            keep(ids);
            tc.end.fill(kept.size());
        } else {
            quarters.split();
            for (int q = 0; q < 4; ++q) {
                tc.begin[q] = kept.size();
                if (quarters.used(q)) {
                    auto& narrowed = buffers.quarterSegments;
                    narrowed.clear();
                    chainTrees_.narrow(ids, quarters.lo(q), quarters.hi(q), farthest, narrowed);
                    keep(narrowed);
                }
                tc.end[q] = kept.size();
            }
        }
        out.chains.push_back(tc);
    }
}

}  // namespace nenrin
