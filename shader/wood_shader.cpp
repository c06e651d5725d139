#include "shader/wood_shader.h"

#include <algorithm>
#include <cmath>

#include "grain/growth_terms.h"
#include "grain/knot_look.h"
#include "grain/wood_colour.h"
#include "shader/bark.h"
#include "shader/colour_line.h"
#include "shader/saw_marks.h"
#include "shader/wood_anatomy.h"

namespace nenrin {

namespace {

/// The relief is the late-wood profile filtered over at least this many years, so its slope
/// stays finite at the sharp late-to-early-wood step.
constexpr double kReliefMinWidth = 0.04;

/// Micro-structure weight for a footprint `size` (m) and cell size: full below half a cell,
/// gone past two cells.
double microWeight(double size, double cell) {
    return std::clamp(1 - (size / cell - 0.5) / 1.5, 0.0, 1.0);
}

}  // namespace

WoodShader::WoodShader(const GrowthField& field, Finish finish)
    : field_(&field),
      finish_(std::move(finish)),
      rings_(lateWoodShape(field.params().colour)),
      gradientStep_(std::max(1e-6, 0.02 * field.params().radialSpeed)),
      colourLine_(
          field.params().anatomy.colourLine
              ? woodColourLine(field.params().colour.earlyWood, field.params().colour.lateWood)
              : Rgb{1, 1, 1}) {}

void WoodShader::evaluate(std::span<const Vec3> treePoints, std::span<WoodSample> out,
                          GrowthScratch& scratch, std::vector<GrowthSample>& samples) const {
    samples.resize(treePoints.size());
    field_->evaluateBatch(treePoints, samples, scratch);
    const ColourParams& colour = field_->params().colour;
    const double felled = field_->params().fellingTime;
    const LatewoodTiming& timing = field_->latewoodTiming();
    for (size_t i = 0; i < treePoints.size(); ++i) {
        bool outside = felled > 0 && samples[i].T > felled;
        out[i].coverage = outside ? 0 : 1;
        out[i].albedo = outside ? Rgb{}
                                : woodColour(samples[i], treePoints[i], colour,
                                             rings_.lateWood(timing.profileTime(
                                                 colourTime(samples[i], treePoints[i], colour))),
                                             1.0);
        out[i].T = samples[i].T;
        out[i].knot = samples[i].knot;
    }
}

Vec3 WoodShader::applyAnatomy(const GrowthSample& s, const Vec3& point, const SurfaceFootprint& f,
                              double endGrain, double ringTime, WoodSurfaceSample& o) const {
    // Fibres, pores and rays about the trunk's axis, and inside a knot about its branch's:
    // there the rays radiate from the knot's pith and the fibres follow it.
    // On end grain the cells' own texture (fibres, speckle) and the streaks, ring tones and
    // vessels each show as strongly as the grain's end_grain settings say.
    const ColourParams& colour = field_->params().colour;
    const double cellContrast = 1 + colour.endGrainTexture * endGrain;
    const double otherContrast = 1 + colour.endGrainContrast * endGrain;
    AnatomyParams anatomy = field_->params().anatomy;
    anatomy.fibreAmplitude *= cellContrast;
    anatomy.speckleAmplitude *= cellContrast;
    anatomy.streakAmplitude *= otherContrast;
    anatomy.ringTone *= otherContrast;
    anatomy.poreDarkening *= otherContrast;
    // Conifer cells stand in radial files, which a side face cut near the radius shows as
    // cells drawn out across the fibre; on end grain, at a photograph's 0.2 mm a pixel, a
    // sawn or planed face shows round grains instead (Mokume H11's end faces): drawn out
    // there, the speckle read as grey radial fur.
    if (anatomy.speckleRadial > 0)
        anatomy.speckleRadial += (anatomy.speckleSize - anatomy.speckleRadial) * endGrain;
    const bool knotted = s.knotChain >= 0 && s.knot > 0;
    const double inKnot = knotted ? smoothstep(0.3, 0.6, s.knot) : 0.0;
    AnatomySample a =
        woodAnatomy(anatomy, s, point, o.gradientT, f.dpdx, f.dpdy, f.diameter, 1 - inKnot);
    o.albedo = alongColourLine(o.albedo, a, colourLine_);
    Vec3 relief = a.reliefGradient;
    if (inKnot > 0) {
        // (At the time the colour reads the rings at: the knot's ring tone and bands wobble
        // with its late wood.)
        AnatomySample k = woodAnatomy(anatomy, {s.knotOffset, s.knotAxisDirection}, ringTime, point,
                                      o.gradientT, f.dpdx, f.dpdy, f.diameter, inKnot);
        o.albedo = alongColourLine(o.albedo, k, colourLine_);
        relief = relief + k.reliefGradient;
    }
    return relief;
}

void WoodShader::evaluateSurface(std::span<const Vec3> treePoints,
                                 std::span<const SurfaceFootprint> footprints,
                                 std::span<WoodSurfaceSample> out, WoodScratch& scratch) const {
    const size_t n = treePoints.size();
    const double h = gradientStep_;
    // Each point with its three forward-difference neighbours, side by side so that every run
    // of 64 evaluations stays compact (the field prunes candidates per run).
    scratch.points.resize(4 * n);
    for (size_t i = 0; i < n; ++i) {
        const Vec3& p = treePoints[i];
        scratch.points[4 * i] = p;
        scratch.points[4 * i + 1] = p + Vec3{h, 0, 0};
        scratch.points[4 * i + 2] = p + Vec3{0, h, 0};
        scratch.points[4 * i + 3] = p + Vec3{0, 0, h};
    }
    scratch.samples.resize(4 * n);
    field_->evaluateBatch(scratch.points, scratch.samples, scratch.growth, 4);

    const ColourParams& colour = field_->params().colour;
    const double felled = field_->params().fellingTime;
    const LatewoodTiming& timing = field_->latewoodTiming();
    for (size_t i = 0; i < n; ++i) {
        const GrowthSample& s = scratch.samples[4 * i];
        WoodSurfaceSample& o = out[i];
        Vec3 anatomyRelief;
        o.T = s.T;
        o.knot = s.knot;
        o.deadKnot = s.deadKnot;
        o.gradientT = Vec3{scratch.samples[4 * i + 1].T - s.T, scratch.samples[4 * i + 2].T - s.T,
                           scratch.samples[4 * i + 3].T - s.T} /
                      h;

        double width = 0, size = 0;
        if (!footprints.empty()) {
            const SurfaceFootprint& f = footprints[i];
            width =
                std::max(std::abs(dot(o.gradientT, f.dpdx)), std::abs(dot(o.gradientT, f.dpdy)));
            size = std::sqrt(std::max(lengthSquared(f.dpdx), lengthSquared(f.dpdy)));
            if (size == 0 && f.diameter > 0) {
                width = length(o.gradientT) * f.diameter;
                size = f.diameter;
            }
        }
        o.ringFilterWidth = width;
        // The year's own late-wood share: the profile is read at the warped time (inside a
        // knot, wobbled: grain/knot_look.h).
        double warp = 1;
        const double ringTime = colourTime(s, treePoints[i], colour);
        const double profileT = timing.profileTime(ringTime, &warp);
        o.lateWood = rings_.filtered(profileT, width * warp);

        bool outside = felled > 0 && s.T > felled;
        o.coverage = outside ? 0 : 1;
        o.albedo = outside ? barkAlbedo(s, treePoints[i])
                           : woodColour(s, treePoints[i], colour, o.lateWood,
                                        microWeight(size, colour.microCellSize), size);

        // Fibres follow the growth axis (the branch's inside a knot) and lie in the ring
        // surface: remove the part along grad T, which bends them around knots.
        Vec3 axis = s.axisDirection;
        const bool knotted = s.knotChain >= 0 && s.knot > 0;
        if (knotted) {
            Vec3 branch = s.knotAxisDirection;
            if (dot(branch, axis) < 0) branch = -branch;
            axis = normalize(axis * (1 - s.knot) + branch * s.knot);
        }
        double g2 = lengthSquared(o.gradientT);
        Vec3 along = g2 > 0 ? axis - o.gradientT * (dot(axis, o.gradientT) / g2) : axis;
        o.fibre = lengthSquared(along) > 1e-12 ? normalize(along) : axis;
        // How much of the face is end grain (the normal along the fibre).
        const double endGrain =
            !footprints.empty() && lengthSquared(footprints[i].normal) > 0
                ? endGrainWeight(std::abs(dot(normalize(footprints[i].normal), o.fibre)))
                : 0.0;
        if (field_->params().anatomy.enabled && !outside)
            anatomyRelief = applyAnatomy(s, treePoints[i],
                                         footprints.empty() ? SurfaceFootprint{} : footprints[i],
                                         endGrain, ringTime, o);
        if (!footprints.empty() && !outside && finish_.sawMarks > 0) {
            const SurfaceFootprint& f = footprints[i];
            const SawMarkSample m = sawMarks(finish_, treePoints[i], f.dpdx, f.dpdy, endGrain);
            o.albedo = o.albedo * (1 + m.brightness);
            anatomyRelief = anatomyRelief + m.reliefGradient;
        }
        if (!footprints.empty() && !outside && lengthSquared(footprints[i].normal) > 0)
            o.albedo = endGrainAlbedo(
                o.albedo, std::abs(dot(normalize(footprints[i].normal), o.fibre)), colour);
        // A reflectance: the strongest texture a grain allows (end grain multiplies it) and saw
        // marks could lift a light wood's past 1, a surface giving back more than it gets.
        o.albedo = {std::min(o.albedo.r, 1.0), std::min(o.albedo.g, 1.0),
                    std::min(o.albedo.b, 1.0)};

        double slope =
            rings_.filteredSlope(profileT, std::max(width * warp, kReliefMinWidth)) * warp;
        // Past a footprint of a ring or so the relief averages out: fade it with the filter.
        double fade = 1 / (1 + width * width * 4);
        o.reliefGradient = o.gradientT * (finish_.bumpDepth * slope * fade) + anatomyRelief;
        o.meanReliefGradient = o.gradientT * (finish_.bumpDepth * slope) + anatomyRelief;
    }
}

}  // namespace nenrin
