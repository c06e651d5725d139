#pragma once
/// A seeded stochastic ring-width series for trees that record none of their own (grain key
/// "rings", docs/grain-format.md). Real ring series (dendrochronology; ../shared data/rings)
/// have three parts, and so does this model:
///  - an age trend: wide juvenile rings that narrow outward, a negative exponential
///    g(t) = 1 + (J - 1) exp(-t / tau), normalised so that the series' mean width is `meanWidth`;
///  - year-to-year variation: log-normal, AR(1) in log width with lag-1 correlation phi and a
///    standard deviation that gives the requested coefficient of variation;
///  - a climate signal: a share of each year's innovation comes from a series drawn from
///    `climateSeed` alone, so trees with one climate seed (one stand) have correlated rings
///    (their common signal), and trees with different tree seeds still differ.
/// Targets from measured series (data/rings, docs/grain-format.md): CV 0.4-0.8 with the trend,
/// lag-1 autocorrelation 0.5-0.75, mean sensitivity 0.2-0.6.

#include <cstdint>
#include <vector>

namespace nenrin {

struct RingModelParams {
    bool enabled = false;
    double meanWidth = 0;          ///< m; 0 = the grain's radial_speed
    double juvenileFactor = 2.2;   ///< J: ring width at the pith relative to the asymptote
    double juvenileYears = 12;     ///< tau, years: how fast the juvenile rings narrow
    double variation = 0.35;       ///< CV of the detrended widths (log-normal)
    double autocorrelation = 0.6;  ///< phi: lag-1 correlation of the log widths
    double climateShare = 0.5;     ///< share of the innovation variance common to the stand
    int years = 0;                 ///< series length; 0 = felling time (or 150 years)
    uint64_t seed = 1;             ///< this tree
    uint64_t climateSeed = 1;      ///< the stand's climate
    /// Use the model even when the skeleton records ring widths, at their mean width and
    /// length: for imports that record only a mean (Gran_1's CT log has no ring widths).
    bool replaceRecorded = false;
};

/// The widths (m) of `years` years (> 0) with mean width `meanWidth` (> 0, m).
std::vector<double> generateRingWidths(const RingModelParams& params, int years, double meanWidth);

}  // namespace nenrin
