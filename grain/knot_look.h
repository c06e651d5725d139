#pragma once
/// How a knot looks (Momoi 4.4, extended): from the knot geometry of a growth sample (its
/// share, the branch's axis and the knot's section radius) the darkening and tint weight of the
/// knot wood. Knot wood is compression wood, darker towards its pith (the dark core); a dead,
/// encased knot is ringed by the branch's bark, a dark band of a stated width in metres just
/// inside its edge all round, and often opened by a drying check running out from its pith.
/// Round the knot the stem's own wood is often discoloured (resin, compression wood): a halo
/// drawn out along the stem.

#include "grain/grain_params.h"
#include "grain/growth_field.h"

namespace nenrin {

struct KnotLook {
    double darkening = 0;     ///< relative darkening, 0..0.95
    double tint = 0;          ///< weight of the knot tint, 0..1
    double deadFraction = 0;  ///< how much of the knot is dead, picks dead_tint over tint
    double rim = 0;           ///< coverage of the dead knot's bark ring, 0..1 (tests, AOVs)
    double check = 0;         ///< coverage of a drying check, 0..1
};

/// `footprint` (m) is the pixel's size on the surface: the rim and the checks are box-filtered
/// over it (0 = a point sample, drawn sharp).
KnotLook knotLook(const GrowthSample& sample, const ColourParams& colour, double footprint = 0);

/// The weight of `colour.knotHaloTint` at a point of the stem (`treePoint`, tree space): 1 out
/// to the knot's edge, fading to 0 `knotHaloWidth` beyond it across the stem and
/// `knotHaloAxial` times that along it, the reach varied by half either way by a value noise
/// of the halo's own scale so that its edge is patchy, as resin soaks in. The caller keeps it
/// off the knot wood, which has its own tint. Faded out where the knot share falls under 0.1
/// (the branch's term leaving the junction's reach); 0 where the field names no branch or the
/// width is 0.
double knotHalo(const GrowthSample& sample, const Vec3& treePoint, const ColourParams& colour);

/// Years to add to T where the colour reads the ring profile (the late-wood share): a knot's
/// rings are not the perfect circles that the distance from a straight branch axis draws
/// (H11's wobble, run closer and apart), so a value noise of `knotRingWobbleScale` (two
/// octaves, tree space) moves them by up to `knotRingWobble` years, with the knot tint's
/// weight: 0 outside knots, and the field's T (the knot's shape) is left as it is.
double knotRingWobble(const GrowthSample& sample, const Vec3& treePoint,
                      const ColourParams& colour);

/// The time the ring profile is read at: T and, inside knots, knotRingWobble.
inline double colourTime(const GrowthSample& sample, const Vec3& treePoint,
                         const ColourParams& colour) {
    return sample.T + knotRingWobble(sample, treePoint, colour);
}

}  // namespace nenrin
