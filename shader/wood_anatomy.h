#pragma once
/// Wood anatomy at close range: fibre streaks, vessels (pores), rays and resin canals, drawn in
/// the local wood frame of a trunk point: the radial distance rho and azimuth theta about the
/// trunk axis (rays are sheets of constant theta: lines across the rings on end grain), the
/// growth time T (rings: ring-porous vessels sit in the early-wood band), and the position z
/// along the axis (fibres, vessels and rays are long along it).
///
/// Every feature is filtered over the pixel footprint: it fades to its mean (the same average
/// colour) once it is smaller than about a pixel, so a distant board neither aliases nor
/// changes tone. Vessels and resin canals (continuous tubes that wander across the fibre, so
/// side grain shows dashes and end grain every one) keep their area under the filter until
/// the footprint reaches half their spacing: a vessel smaller than a pixel still darkens it by
/// its share. Point samples (footprint 0) draw the features sharp.

#include <algorithm>

#include "grain/anatomy_params.h"
#include "grain/growth_field.h"
#include "grain/rgb.h"

namespace nenrin {

struct AnatomySample {
    double brightness = 1;  ///< the cells', streaks', rings' tones', rays' and resin's factor
    Rgb pores{1, 1, 1};     ///< the open vessels' darkening, per channel (their tint)
    Vec3 reliefGradient;    ///< added to the relief gradient (pits of open pores), tree space
    double pore = 0;        ///< pore coverage 0..1 (for tests and AOVs)
    double ray = 0;         ///< ray coverage 0..1
    /// What multiplies the albedo with the tones grey: brightness x pores, each channel at
    /// least 0 (the parser bounds each strength, but end grain multiplies them up to 5 x:
    /// strong noise or deep pores could take it below zero). shader/colour_line.h takes the
    /// tones along the wood's colour line instead.
    Rgb filter() const {
        return {std::max(0.0, brightness * pores.r), std::max(0.0, brightness * pores.g),
                std::max(0.0, brightness * pores.b)};
    }
};

/// `gradT` is grad T at the point (years/m); `dpdx`, `dpdy` the pixel's footprint on the
/// surface (tree space, m; both zero = a point sample), or `diameter` > 0 for an isotropic one;
/// `weight` scales everything (the shader blends the trunk's and a knot's anatomy with it).
AnatomySample woodAnatomy(const AnatomyParams& params, const GrowthSample& sample,
                          const Vec3& treePoint, const Vec3& gradT, const Vec3& dpdx,
                          const Vec3& dpdy, double diameter = 0, double weight = 1);

/// The axis the anatomy is drawn about: the trunk's in clear wood, a branch's in its knot
/// (rays then radiate from the knot's pith and fibres run along the branch).
struct AnatomyAxis {
    Vec3 offset;     ///< the point minus its nearest axis point
    Vec3 direction;  ///< the axis tangent there
};
/// The same about a given axis, `T` the sample's growth time.
AnatomySample woodAnatomy(const AnatomyParams& params, const AnatomyAxis& axis, double T,
                          const Vec3& treePoint, const Vec3& gradT, const Vec3& dpdx,
                          const Vec3& dpdy, double diameter = 0, double weight = 1);

}  // namespace nenrin
