#pragma once
/// What the wood looks like under a loupe (grain key "anatomy", docs/grain-format.md): fibres,
/// vessels (pores), rays and resin canals, as a species has them. Their sizes are in metres;
/// the shader (shader/wood_anatomy.h) draws them in the local wood frame and fades each to its
/// mean once it is smaller than the pixel footprint.

#include <cstdint>

#include "grain/rgb.h"

namespace nenrin {

enum class PoreKind {
    None,           ///< conifers: no vessels
    RingPorous,     ///< a band of large vessels in the early wood (oak, ash, zelkova)
    DiffusePorous,  ///< small vessels throughout the ring (beech, maple, cherry, walnut)
};

struct AnatomyParams {
    bool enabled = false;
    uint64_t seed = 1;
    /// The brightness changes below taken along the wood's own colour line (darker = more
    /// saturated, as late wood against early wood) instead of grey; luminance as grey
    /// (shader/colour_line.h).
    bool colourLine = false;
    /// Fibre streaks: brightness noise drawn out along the fibre.
    double fibreAmplitude = 0.05;  ///< relative brightness (+-)
    double fibreWidth = 0.0004;    ///< m across the fibre
    double fibreLength = 0.03;     ///< m along it
    /// Streaks: broad bands of tone along the grain, millimetres wide and centimetres long
    /// (mineral streaks, growth-rate changes within a ring).
    double streakAmplitude = 0;  ///< relative brightness (+-)
    double streakWidth = 0.003;  ///< m across the fibre
    double streakLength = 0.05;  ///< m along it
    /// Ring tone: each year's ring a little lighter or darker than the next (the year's
    /// density), seeded per ring.
    double ringTone = 0;  ///< relative brightness (+-)
    /// Speckle: the cells' own granular texture, a few fibres across.
    double speckleAmplitude = 0;   ///< relative brightness (+-)
    double speckleSize = 0.00015;  ///< m across the fibre (tangentially)
    /// m radially: conifer cells line up in radial files, so on end grain the speckle is drawn
    /// out towards the pith; <= 0: speckleSize.
    double speckleRadial = 0;
    double speckleLength = 0.0005;  ///< m along it
    /// Vessels: open tubes along the fibre, dots on end grain, dashes on side grain.
    PoreKind pores = PoreKind::None;
    double poreDiameter = 0.0002;  ///< m
    double poreSpacing = 0.0008;   ///< m between neighbouring vessels
    double poreLength = 0.003;     ///< m along the fibre over which a vessel wanders by its radius
    double poreBand = 0.25;        ///< ring-porous: share of the ring (from its start) with pores
    double poreDarkening = 0.45;   ///< relative darkening inside an open pore
    /// Per channel, the share of that darkening: open vessels of oak or chestnut are brown,
    /// not grey, so blue darkens most (e.g. [0.8, 0.9, 1]).
    Rgb poreTint{1, 1, 1};
    double poreDepth = 0.3;  ///< relief slope at a pore's wall (m/m): the pits of the normal
    /// Rays: ribbons running out from the pith: lines on end grain, flecks on quarter-sawn
    /// faces, short dashes on flat-sawn faces.
    double raySpacing = 0.0015;  ///< m between rays (at 0.1 m from the pith)
    double rayWidth = 0.0001;    ///< m, tangential thickness
    double rayHeight = 0.0008;   ///< m along the fibre
    double rayContrast = -0.08;  ///< relative brightness change: < 0 darker, > 0 lighter
    /// Resin canals (pine, spruce, larch, Douglas fir): sparse dark ducts in the late wood.
    double resinSpacing = 0;  ///< m between canals; 0 = none
    double resinDiameter = 0.0001;
    double resinDarkening = 0.35;
};

}  // namespace nenrin
