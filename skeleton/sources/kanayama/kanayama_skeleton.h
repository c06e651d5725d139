#pragma once
/// Converts a Kanayama shoot history into a Skeleton: chain 0 = the main stem (the seedling
/// and its terminal continuations), every other chain = a lateral shoot and its terminal
/// continuations over the years, starting on the parent's node. Node birth times are the year
/// plus the node's share of the elongation season; radii come from the simulated
/// cross-sections; gamma is a branch's radial growth relative to the trunk base over the same
/// years; branches that died keep their death time (dead knots, also when the living tree has
/// shed them); shoots cut away (leader removal) are not part of the wood. Ring widths are the
/// trunk base's yearly radial increments.

#include <vector>

#include "skeleton/skeleton.h"
#include "skeleton/sources/kanayama/kanayama_growth.h"

namespace nenrin {

/// `trunkBaseRadius[y]` is the seedling shoot's radius (m) at the end of year y.
Skeleton buildKanayamaSkeleton(const std::vector<KanayamaShoot>& shoots,
                               const std::vector<double>& trunkBaseRadius,
                               const KanayamaSpecies& species);

}  // namespace nenrin
