#pragma once
/// The bark past the felled log's wood (coverage 0): dark fissures between lighter plates,
/// drawn out along the trunk, in the frame about the trunk axis. Point-sampled; its plates are
/// centimetres wide, so a pixel seldom holds more than one.

#include "grain/growth_field.h"
#include "grain/rgb.h"

namespace nenrin {

/// Albedo of the bark at `treePoint` (`sample` gives the nearest trunk point and axis).
Rgb barkAlbedo(const GrowthSample& sample, const Vec3& treePoint);

}  // namespace nenrin
