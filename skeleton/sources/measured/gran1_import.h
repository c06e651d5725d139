#pragma once
/// Importer for CT-measured logs in the Gran_1 layout (Larsson et al. 2022, data/gran1/): a
/// pith polyline, a bark-radius map per height and azimuth, and knots given as parametric
/// curves from the pith. The pith becomes the trunk; every knot becomes a branch following its
/// curve, dying (a dead, encased knot) where the stem's radius reached the knot's death
/// distance. The bark map fixes the ring widths: the log's butt radius over the ring count.
/// Format and readings: docs/trees.md ("Gran_1").

#include <string>

#include "skeleton/skeleton.h"

namespace nenrin {

struct Gran1Options {
    /// Rings at the log's butt (the CT data do not count them). With the butt's mean bark
    /// radius this sets the ring width; the tree is felled at this age.
    double rings = 60;
    /// m/year; 0 = derived from the bark's taper (ring width / taper), clamped to 0.1 … 1.
    double heightGrowth = 0;
    double branchGrowth = 0.2;  ///< m/year: how fast a branch tip moves out from the pith
    double knotGamma = 0.125;   ///< a knot's radial speed relative to the stem's (eq. 3')
    double diebackExponent = 1;
};

struct Gran1Log {
    Skeleton skeleton;
    double ringWidth = 0;     ///< m/year
    double heightGrowth = 0;  ///< m/year, as used
    double fellingAge = 0;    ///< years: the bark at the butt is this iso-surface of T
    double meanButtRadius = 0, meanTopRadius = 0;  ///< m, from the bark map
    double minBarkRadius = 0, maxBarkRadius = 0;   ///< m: eccentricity of the real log
    size_t knots = 0, knotsSkipped = 0;            ///< skipped: dead at once (I < 0.1 mm)
};

/// Reads `<folder>/<name>_pith.json`, `_radii.json` and `_knots.json` (mm, radians).
/// `prefix` is the path up to the underscore, e.g. "data/gran1/Gran_1".
Gran1Log importGran1(const std::string& prefix, const Gran1Options& options = {});

}  // namespace nenrin
