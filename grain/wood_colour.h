#pragma once
/// The wood colour of section 3 of Momoi's paper, from a growth sample: early/late wood (eq. 6),
/// heartwood/sapwood offsets, micro-structure (4.6) and knot emphasis (4.4).

#include "grain/growth_field.h"
#include "grain/rgb.h"

namespace nenrin {

/// `treePoint` is the (unswayed) tree-space point: the micro-structure is fixed to the wood.
Rgb woodColour(const GrowthSample& sample, const Vec3& treePoint, const ColourParams& colour);

}  // namespace nenrin
