#pragma once
/// The yearly series the growth field grows by, from the skeleton's records and the grain's
/// ring model: the ring widths its thickening follows (RadialGrowth) and when each year's late
/// wood begins (LatewoodTiming). Built once, when a GrowthField is made.

#include <vector>

#include "grain/grain_params.h"
#include "grain/growth_terms.h"
#include "grain/latewood_timing.h"
#include "skeleton/skeleton.h"

namespace nenrin {

/// The ring widths (m/year) of the field: the skeleton's recorded widths, or the grain's
/// stochastic series (ring_model.h) where its ring model is on and the skeleton records none
/// or it replaces them. Empty: constant speed Sb.
struct FieldRings {
    std::vector<double> widths;
    bool modelled = false;  ///< the widths are the ring model's
};
/// The modelled series is as long as the tree lived (the felling time, else 150 years), or as
/// the recorded one, at the recorded mean width (else the grain's Sb) unless the ring model
/// sets its own length and mean.
FieldRings fieldRingWidths(const Skeleton& skeleton, const GrainParams& params);

/// The late-wood share S of a transition shape: 1 minus the ring phase at which its E crosses
/// 1/2 (found by bisection).
double profileLateWoodShare(const LateWoodShape& shape);

/// When each year's late wood begins: the skeleton's measured shares; else, for modelled
/// widths, shares that grow in narrow rings as the square root of the mean width over the
/// year's (late wood varies less from year to year than early wood), within [0.05, 0.9];
/// else none (empty).
LatewoodTiming fieldLatewoodTiming(const Skeleton& skeleton, const FieldRings& rings,
                                   const LateWoodShape& shape);

}  // namespace nenrin
