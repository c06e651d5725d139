#pragma once
/// The first, cheap tests of the branch pass (docs/model.md, "How evaluation is organised",
/// step 5) for one tile chain at every point of a chunk at once: behind the chain's plane F,
/// born too late, or its kept segments' box out of reach. Written over arrays so that the loop
/// vectorises; each lane computes what the per-point test computed, in the same order.
/// Internal to grain/.

#include <array>
#include <cstdint>
#include <span>

#include "grain/field_passes.h"

namespace nenrin {

/// What the branch pass's tests read of the field.
struct ReachBounds {
    std::span<const FieldSegment> segments;
    double speedBound;  ///< GrowthField::speedBound_
    double delta;       ///< of the age warp, eq. 8
    double reach;       ///< of the junction's cut-off
};

/// Fills lanes [0, n) of `out` for the first n points; `trunkTimes`: their T1.
void reachTests(const TileChain& chain, const ReachBounds& bounds, const PointLanes& points,
                size_t n, const double* trunkTimes, ReachLanes& out);

}  // namespace nenrin
