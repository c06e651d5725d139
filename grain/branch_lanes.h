#pragma once
/// The branch pass's per-point work for one tile chain, lane by lane (docs/model.md, "How
/// evaluation is organised", step 5): where measureChains has found each point's nearest of
/// the chain's kept segments in lanes, the tests that may drop the chain there, its path time
/// (chainPathTime's no-blend case) and the term's reach weight and dead share, in one loop
/// over the lanes written with vector types. Each lane computes what the per-point code
/// computes, in the same order: the same bits. Only for fields with plain thickening
/// (GrowthField::plainThickening_: no age warp either). Internal to grain/.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "grain/field_passes.h"
#include "grain/reach_lanes.h"

namespace nenrin {

/// The most kept segments branchLanes takes for one chain.
constexpr size_t kBranchLaneSegments = 12;

/// The lanes' inputs: a chunk's n points and their nearest of the segments `ids` (`nearest`),
/// their trunk times and the chain's reachTests there. (Not for a chain whose kept segments
/// differ by quarter of the chunk: there each lane's segment is one of more, for fewer lanes,
/// and the per-point code costs less.)
struct BranchLaneInputs {
    std::span<const uint32_t> ids;  ///< at most kBranchLaneSegments
    const PointLanes& points;
    size_t n;
    const NearestLanes& nearest;
    const double* trunkTimes;
    const ReachLanes& reach;
};

/// Fills lanes [0, n) of `out` (lanes up to the next multiple of 4 hold what is not used).
void branchLanes(const ReachBounds& bounds, const BranchLaneInputs& in, BranchLanes& out);

}  // namespace nenrin
