#pragma once
/// The wood colour of section 3 of Momoi's paper, from a growth sample: early/late wood (eq. 6),
/// heartwood/sapwood offsets, micro-structure (4.6) and the knots' look (4.4, grain/knot_look.h).

#include "grain/growth_field.h"
#include "grain/rgb.h"

namespace nenrin {

/// `treePoint` is the (unswayed) tree-space point: the micro-structure is fixed to the wood.
Rgb woodColour(const GrowthSample& sample, const Vec3& treePoint, const ColourParams& colour);
/// The same with the early/late-wood mix E given (a renderer passes E averaged over its pixel
/// footprint) and the micro-structure scaled by `microWeight` (0 once its cells are smaller
/// than a pixel: their mean is 0, point samples of them would only add noise); the knots'
/// bark rings and checks are filtered over `footprint` (m, 0 = a point sample).
Rgb woodColour(const GrowthSample& sample, const Vec3& treePoint, const ColourParams& colour,
               double lateWood, double microWeight, double footprint = 0);

/// The end-grain term: `albedo` seen on a face whose normal makes |cos| = `cosFibre` with the
/// fibre (1 = cut straight across it, 0 = along it).
Rgb endGrainAlbedo(const Rgb& albedo, double cosFibre, const ColourParams& colour);
/// How much of a face is end grain: |cos(normal, fibre)|^4, 1 across the fibre, 0 along it.
double endGrainWeight(double cosFibre);

}  // namespace nenrin
