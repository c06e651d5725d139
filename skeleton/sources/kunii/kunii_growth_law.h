#pragma once
/// Im, Shinagawa & Kunii's growth law (eq. 1) and the paper's cusp analysis of it (eqs. 2-3).
///
/// A tree of species g (small g = shade tolerant, large g = intolerant) receiving irradiance I
/// grows at the relative rate
///
///     (1/w) dw/dt = a (g + b) (1 - exp(-(c (g - d)^2 + e) (I - f g)))          (1)
///
/// so its maximum rate a (g + b) rises with g and so does its compensation point I_c = f g.
/// The paper does not print a..f; docs/stand-kunii.md explains the values chosen here.
///
/// The analysis: to first order 1 - exp(-x) ~ x, so (1) becomes a quartic in g. Substituting
/// g = G + (I + f (2d - b)) / (4f) removes the cubic term and leaves
/// -alpha (G^4 - p(I) G^2 - q(I) G + r(I))  (2); the best-suited species sits on a stationary
/// point 4 G^3 - 2 p G - q = 0  (3), a cusp catastrophe: where three stationary points exist
/// the best species depends on where it came from (hysteresis).

#include <vector>

namespace nenrin {

/// The constants of eq. 1. Irradiance is relative (1 = full sun above the canopy); rates are
/// per year for a reference tree (see StandOptions::referenceWeight).
struct KuniiGrowthLaw {
    double a = 0.5;  ///< 1/year: scale of the maximum rate a (g + b)
    double b = 0.2;  ///< offset of the maximum rate (keeps g = 0 growing)
    double c = 20;   ///< curvature of the light-response steepness in g
    double d = 0.5;  ///< species whose light response is the most gradual
    double e = 0.3;  ///< minimum light-response steepness
    double f = 0.3;  ///< compensation point per unit g: I_c = f g
};

/// Eq. 1: relative growth rate (1/year) of species g at irradiance I.
double relativeGrowthRate(const KuniiGrowthLaw& law, double g, double irradiance);
/// The irradiance where eq. 1 is zero (photosynthesis = respiration): f g.
double compensationIrradiance(const KuniiGrowthLaw& law, double g);
/// d(eq. 1)/dI at the compensation point: a (g + b) (c (g - d)^2 + e).
double compensationSlope(const KuniiGrowthLaw& law, double g);

/// The depressed quartic of eq. 2 at one irradiance: the first-order expansion of eq. 1 is
/// -alpha (G^4 - p G^2 - q G + r) with g = G + shift.
struct CuspQuartic {
    double alpha = 0, p = 0, q = 0, r = 0;
    double shift = 0;  ///< (I + f (2d - b)) / (4f)
    /// The G^3 coefficient left after the shift: zero up to rounding (a check of the paper's
    /// substitution).
    double cubicResidue = 0;
};
CuspQuartic cuspQuartic(const KuniiGrowthLaw& law, double irradiance);
/// The first-order expansion itself, a (g + b) (c (g - d)^2 + e) (I - f g), for checks.
double linearisedGrowthRate(const KuniiGrowthLaw& law, double g, double irradiance);

/// Species g at the stationary points of eq. 2 (roots of eq. 3), ascending: one or three.
std::vector<double> stationarySpecies(const KuniiGrowthLaw& law, double irradiance);
/// True where eq. 3 has three real roots (two maxima of eq. 2): 8 p^3 > 27 q^2.
bool isBistable(const KuniiGrowthLaw& law, double irradiance);

/// The locally best species reached from `gStart` by climbing eq. 1 (exact, not linearised)
/// within [gMin, gMax]: the species a population that starts at gStart drifts to.
double followBestSpecies(const KuniiGrowthLaw& law, double irradiance, double gStart, double gMin,
                         double gMax);
/// The followed best species along a sequence of irradiances, each step starting from the
/// previous answer: sweeping I up and down shows the hysteresis of the cusp.
std::vector<double> sweepBestSpecies(const KuniiGrowthLaw& law,
                                     const std::vector<double>& irradiances, double gStart,
                                     double gMin, double gMax);
/// The globally best species on a grid of `samples` points over [gMin, gMax].
double globallyBestSpecies(const KuniiGrowthLaw& law, double irradiance, double gMin, double gMax,
                           int samples = 1001);

}  // namespace nenrin
