#pragma once
/// Every term of Momoi's growth-time model (models.md section 1) as a small pure function, so
/// each can be read against the paper and unit-tested alone. GrowthField composes them.
/// Units: metres, years.

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "grain/grain_params.h"
#include "util/vec3.h"

namespace nenrin {

/// Eq. 2: Ta = Da / Sa, the time for the growth tip to travel path length Da at elongation
/// speed Sa. Skeletons carry it as node birth times (the path length to the node over Sa, or
/// any elongation history a growth model gives); along a segment whose start was reached at
/// `startBirth` and end `birthDelta` later, the tip passes fraction t of it at
/// startBirth + t birthDelta, which is Da / Sa for a constant Sa.
inline double elongationTime(double startBirth, double birthDelta, double t) {
    return startBirth + birthDelta * t;
}

/// Eq. 3 / 3': Tb = Db / S, the time for the bark to thicken out over distance Db at radial
/// speed S = Sb gamma f (gamma = 1 on the trunk path; f the product of the speed factors of
/// taper, eq. 9, and direction, eq. 7). Computed as the field keeps it: Db times the segment's
/// 1 / (Sb gamma), then over f, where f = 1 spares the division.
inline double thickeningTime(double distance, double inverseSpeed, double speedFactor) {
    const double years = distance * inverseSpeed;
    return speedFactor != 1 ? years / speedFactor : years;
}

/// Eq. 7: radial speed factor 1 - eps cos(beta); beta is the angle between the sun-ray vector
/// (pointing away from the sun) and the outward bark normal. The sun side (normal facing the
/// sun, cos beta = -1) grows by 1 + eps.
inline double directionFactor(const Vec3& outwardNormal, const Vec3& sunRay, double eps) {
    return 1.0 - eps * dot(sunRay, outwardNormal);
}

/// Eq. 8: ageing, Tb = tb^delta with tb in years: rings narrow outward when delta > 1.
inline double ageWarp(double thickeningYears, double delta) {
    return delta == 1.0 ? thickeningYears : std::pow(thickeningYears, delta);
}

/// Inverse of ageWarp: the thickening years that eq. 8 maps to `years`.
inline double ageUnwarp(double years, double delta) {
    return delta == 1.0 ? years : std::pow(years, 1.0 / delta);
}

/// Eq. 9 with ln(omega) given: omega^Ta as exp(Ta ln omega), half pow's cost where the field
/// makes ln(omega) once (equal to pow's to an ulp or two).
inline double taperFactorFromLog(double elongationYears, double nu, double logOmega) {
    return nu == 0.0 ? 1.0 : 1.0 + nu * std::exp(std::max(elongationYears, 0.0) * logOmega);
}

/// Eq. 9: taper, radial speed factor 1 + nu omega^Ta: the trunk thickens faster near its base.
inline double taperFactor(double elongationYears, double nu, double omega) {
    return taperFactorFromLog(elongationYears, nu, std::log(omega));
}

/// Eq. 10: dieback. After the branch dies at Tlim it stops thickening: its path time grows
/// steeply, T' = T (T / Tlim)^eps, so the trunk overgrows it and the knot stops widening.
inline double dieback(double t, double deathTime, double eps) {
    return t > deathTime ? t * std::pow(t / deathTime, eps) : t;
}

/// Eq. 4, region D of Fig. 3: T = (T1 M1 + T2 M2) / (M1 + M2), where M1 and M2 are the
/// distances to the planes through the joint perpendicular to the two segments; over a chain's
/// members around P (two, or three where P lies in both neighbours' slabs),
/// T = sum M_i T_i / sum M_i, summed in chain order (the same from either end). With two members
/// it is the pair's formula. Where every M_i is 0 (P on every joint plane at once) there is no
/// blend: `unweighted` is returned (the nearest member's own time).
inline double jointBlend(std::span<const double> times, std::span<const double> planeDistances,
                         double unweighted) {
    double weighted = 0, weights = 0;
    for (size_t i = 0; i < times.size(); ++i) {
        weighted += planeDistances[i] * times[i];
        weights += planeDistances[i];
    }
    return weights > 0 ? weighted / weights : unweighted;
}

/// Eq. 5's smooth minimum T = (sum_i w_i E_i^-p)^(-1/p) over path times E_i (T1 for the
/// trunk, T_c / sin(alpha) for a branch), evaluated relative to m = min E_i so a large p
/// cannot overflow: each path contributes junctionTerm(m, E_i, p) (times its weight), and
/// junctionCombine(m, sum, p) gives T. Every term lies in (0, 1]; the trunk's share of the
/// sum is what GrowthSample::knot leaves over.
inline double junctionTerm(double m, double effectiveTime, double p) {
    double x = m / effectiveTime;
    return p == 2.0 ? x * x : std::pow(x, p);
}
inline double junctionCombine(double m, double sum, double p) {
    return m * (p == 2.0 ? 1.0 / std::sqrt(sum) : std::pow(sum, -1.0 / p));
}

/// Eq. 5 over the trunk path and any number of branch paths c, each with a weight w_c:
///   T = (T1^-p + sum_c w_c E_c^-p)^(-1/p),  E_c = T_c / sin(alpha_c),
/// relative to m = min(T1, min_c E_c) > 0. Make it with m and T1, add() the branch paths in a
/// fixed order (the sum's order is part of the answer), then read time().
class JunctionSum {
public:
    JunctionSum(double m, double trunkTime, double p)
        : m_(m), p_(p), trunk_(junctionTerm(m, trunkTime, p)), sum_(trunk_) {}
    /// Adds a branch path of effective time E_c with weight w_c; returns its term
    /// w_c (m / E_c)^p.
    double add(double effectiveTime, double weight) {
        const double term = weight * junctionTerm(m_, effectiveTime, p_);
        sum_ += term;
        return term;
    }
    double time() const { return junctionCombine(m_, sum_, p_); }
    double sum() const { return sum_; }  ///< of every term, the trunk's (m / T1)^p included
    /// The branch paths' share of the sum (GrowthSample::knot).
    double branchShare() const { return (sum_ - trunk_) / sum_; }

private:
    double m_, p_, trunk_, sum_;
};

/// Eq. 5 (our reconstruction, models.md 1.2) for one trunk and one branch path:
///   T = T1                                   if sin(alpha) <= 0 (behind the branch's plane F)
///   T = (T1^-p + (T2 / sin alpha)^-p)^(-1/p) otherwise.
/// p = 2 is T1 T2 / sqrt(T2^2 + (T1 sin alpha)^2), the paper's form; p -> infinity the
/// first-arrival minimum. GrowthField takes the same JunctionSum over all branch paths at once.
inline double junctionBlend(double trunkTime, double branchTime, double sinAlpha, double p) {
    if (sinAlpha <= 0) return trunkTime;
    double branchEffective = branchTime / sinAlpha;
    double m = std::min(trunkTime, branchEffective);
    if (m <= 0) return 0;
    JunctionSum sum(m, trunkTime, p);
    sum.add(branchEffective, 1.0);
    return sum.time();
}

/// Linear interpolation from a (t = 0) to b (t = 1).
inline double mix(double a, double b, double t) { return a + (b - a) * t; }

/// Smooth step from 0 at e0 to 1 at e1.
inline double smoothstep(double e0, double e1, double x) {
    double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3 - 2 * t);
}

/// Share of [lo, hi] under a box filter of width f centred at x (f = 0: the indicator): a
/// band of known width drawn filtered over a pixel's footprint.
inline double boxCoverage(double x, double lo, double hi, double f) {
    if (f <= 1e-12) return x >= lo && x < hi ? 1.0 : 0.0;
    double a = std::clamp(x - 0.5 * f, lo, hi), b = std::clamp(x + 0.5 * f, lo, hi);
    return (b - a) / f;
}

/// Cut-off weight of a branch path in the junction blend, from its effective time
/// T_c / sin(alpha) (the quantity eq. 5 compares with T1): 1 below half of reach x the trunk
/// time, fading smoothly to 0 at reach x the trunk time. With p = 2 and reach = 4 a term is
/// dropped where it would lower T by less than 3 %: the blend stays continuous while far or
/// grazing branches cost nothing (see GrowthField).
inline double junctionReachWeight(double effectiveBranchTime, double trunkTime, double reach) {
    return 1.0 - smoothstep(0.5, 1.0, effectiveBranchTime / (reach * std::max(trunkTime, 1e-9)));
}

/// Eq. 6: late-wood fraction E = sin^n((pi/2) u), u = frac(T): 0 in early wood at the start of
/// the season, rising to 1 in late wood at the ring's end.
double lateWoodFraction(double growthTime, double exponent);

/// A species' early-to-late-wood transition: eq. 6's sine power when `share` is 0 (a gradual
/// rise, as in spruce), or an abrupt step (larch, pine, Douglas fir) into a late-wood band
/// `share` of the ring wide, over a transition `transition` of the ring:
/// E = smoothstep(1 - share - transition/2, 1 - share + transition/2, frac(T)).
/// The step's band need not be flat: conifer cell walls thicken through the whole season, so
/// the early wood darkens a little towards the band (`earlyRise`: E at the band's start, rising
/// quadratically from 0) and the band darkens towards the ring's end (`lateRamp`: E starts the
/// band at 1 - lateRamp and reaches 1 at the boundary). Both keep E monotone within a ring.
struct LateWoodShape {
    double exponent = 6;
    double share = 0;
    double transition = 0.05;
    /// A measured profile (nenrin grain strip): E at evenly spaced ring phases 0 … 1, linearly
    /// interpolated; overrides the two forms above when it has two or more values.
    std::vector<double> table;
    double earlyRise = 0;  ///< 0 … 0.45, with share > 0
    double lateRamp = 0;   ///< 0 … 0.5, with share > 0
};
double lateWoodFraction(double growthTime, const LateWoodShape& shape);
/// The shape a grain's colour parameters give.
inline LateWoodShape lateWoodShape(const ColourParams& c) {
    return {c.lateWoodExponent, c.lateWoodShare, c.lateWoodTransition,
            c.lateWoodProfile,  c.earlyWoodRise, c.lateWoodRamp};
}

/// Heartwood weight (3.2): 1 for T < Th1 (heartwood), 0 for T > Th2 (sapwood), linear between.
inline double heartwoodWeight(double growthTime, double start, double end) {
    if (growthTime <= start) return 1;
    if (growthTime >= end) return 0;
    return (end - growthTime) / (end - start);
}

/// The seeded waves of section 4.5, drawn once from SwayParams (hashing per sample is slow).
struct SwayWaves {
    static constexpr int kWaves = 3;  ///< sines per axis, and harmonics of the radial factor
    double amplitude = 0, radialJitter = 0;
    Vec3 direction[3][kWaves];  ///< wave vectors (1/m) per displaced axis
    double phase[3][kWaves];
    double radialPhase[kWaves], radialDrift[kWaves];  ///< radians, radians per year
};
SwayWaves makeSwayWaves(const SwayParams& sway);

/// Section 4.5, main method: sample-point displacement, a seeded sum of sines of the coordinates;
/// each component is at most the amplitude.
Vec3 swayDisplacement(const Vec3& p, const SwayWaves& waves);

/// Section 4.5, second method: a factor 1 + radialJitter h(azimuth, Ta), |h| <= 1, on Db. The
/// azimuth is that of the outward normal about the skeleton axis, so rings become gently lobed
/// and the lobes drift along the trunk.
double swayRadialFactor(const Vec3& outwardNormal, const Vec3& axis, double elongationYears,
                        const SwayWaves& waves);
/// The plane the azimuth is measured in: two unit vectors square to the axis. The field keeps
/// one per segment (the same for every point of it).
struct SwayFrame {
    Vec3 u, v;
};
SwayFrame swayFrame(const Vec3& axis);
double swayRadialFactor(const Vec3& outwardNormal, const SwayFrame& frame, double elongationYears,
                        const SwayWaves& waves);

/// Section 4.6: micro-structure. A 16 x 16 table of seeded brightness offsets in [-1, 1], tiled
/// on the plane perpendicular to the trunk (tree XY) and projected along it: returns the offset
/// at p (multiply by the amplitude).
double microStructure(const Vec3& p, double cellSize, uint64_t seed);

}  // namespace nenrin
