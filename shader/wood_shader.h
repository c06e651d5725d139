#pragma once
/// The wood as a material: tree-space points in, everything a renderer needs out.
///  - evaluate(): albedo, growth time, knot and the felling mask, one field evaluation per
///    point (bakers, and the renderer's indirect bounces).
///  - evaluateSurface(): the full surface response: the same plus the gradient of T (forward
///    differences, three more evaluations per point), the fibre direction (the growth axis
///    bent into the ring surface, so fibres flow around knots), a late-wood relief gradient
///    for bump mapping, and the ring profile of eq. 6 box-filtered over
///    the pixel footprint (|grad T . dp/dx|) so distant boards show no moire.

#include <span>
#include <vector>

#include "grain/growth_field.h"
#include "grain/rgb.h"
#include "shader/finish.h"
#include "shader/ring_profile.h"

namespace nenrin {

/// Albedo of the bark: what renderers show past the felled log (coverage 0).
inline constexpr Rgb kBarkAlbedo{0.06, 0.04, 0.03};

struct WoodSample {
    Rgb albedo;           ///< scene-linear
    double coverage = 1;  ///< 0 outside the felled log (T past the felling time), else 1
    double T = 0;         ///< growth time, years
    double knot = 0;
};

/// Tree-space offsets from a shading point to the surface points seen through the
/// neighbouring pixels (ray differentials), or an isotropic footprint diameter for hosts
/// without differentials (used when both offsets are zero). All zero = a point sample.
struct SurfaceFootprint {
    Vec3 dpdx, dpdy;
    double diameter = 0;  ///< m
    /// The surface normal (tree space, any length), for the end-grain term; zero = unknown
    /// (no end-grain term).
    Vec3 normal;
};

struct WoodSurfaceSample {
    Rgb albedo;  ///< scene-linear, ring profile filtered over the footprint; the bark outside
    double coverage = 1;         ///< 0 outside the felled log
    double T = 0;                ///< growth time, years
    double knot = 0;             ///< branch share of the junction blend, 0..1
    double deadKnot = 0;         ///< dead part of the knot share
    double lateWood = 0;         ///< E of eq. 6, filtered
    double ringFilterWidth = 0;  ///< years of T under the footprint
    Vec3 fibre;                  ///< unit fibre direction, tree space
    Vec3 gradientT;              ///< grad T, years per metre, tree space
    /// Gradient of the relief height (m/m, tree space): bump mapping tilts the normal by its
    /// component along the surface.
    Vec3 reliefGradient;
    /// The relief's mean slope over the footprint, without the fade the renderer adds past a
    /// ring or so: what a texel of a normal map holds (the host's mip-mapping then averages
    /// further), so a texel on a late-wood edge keeps its tilt.
    Vec3 meanReliefGradient;
};

/// Per-thread buffers.
struct WoodScratch {
    GrowthScratch growth;
    std::vector<Vec3> points;
    std::vector<GrowthSample> samples;
};

class WoodShader {
public:
    /// The field must outlive the shader.
    explicit WoodShader(const GrowthField& field, Finish finish = Finish{});

    const GrowthField& field() const { return *field_; }
    const Finish& finish() const { return finish_; }

    /// Evaluates a spatially coherent batch of tree-space points.
    void evaluate(std::span<const Vec3> treePoints, std::span<WoodSample> out,
                  GrowthScratch& scratch, std::vector<GrowthSample>& samples) const;

    /// The full surface response. `footprints` is empty (point samples) or one per point.
    void evaluateSurface(std::span<const Vec3> treePoints,
                         std::span<const SurfaceFootprint> footprints,
                         std::span<WoodSurfaceSample> out, WoodScratch& scratch) const;

private:
    /// Multiplies the albedo by the anatomy's texture; returns its relief gradient. `endGrain`
    /// (0-1, endGrainWeight) strengthens the cells' own texture by the grain's
    /// `end_grain.texture` and its streaks, ring tones and vessels by `end_grain.contrast`, and
    /// rounds the cells (their radial files are a side-grain look). `ringTime`: the time the
    /// colour reads the rings at (colourTime), which a knot's anatomy follows.
    Vec3 applyAnatomy(const GrowthSample& s, const Vec3& point, const SurfaceFootprint& f,
                      double endGrain, double ringTime, WoodSurfaceSample& o) const;

    const GrowthField* field_;
    Finish finish_;
    RingProfile rings_;
    double gradientStep_;  ///< of the forward differences for grad T (m): 2 % of a ring
    Rgb colourLine_;       ///< the anatomy's tones are taken along it (shader/colour_line.h)
};

}  // namespace nenrin
