#pragma once
/// The early/late-wood profile of eq. 6 over one ring, E(u) = sin(pi u / 2)^n, u = frac(T), and
/// its box-filtered average over a range of growth times. A distant board squeezes many rings
/// into one pixel; averaging E over the pixel's range of T (its footprint times |grad T|)
/// instead of point-sampling it removes the moire at any sample count.

#include <vector>

#include "grain/growth_terms.h"

namespace nenrin {

class RingProfile {
public:
    /// `exponent` is n of eq. 6 (late_wood_exponent); larger = narrower late-wood band.
    explicit RingProfile(double exponent)
        : RingProfile([exponent] {
              LateWoodShape shape;
              shape.exponent = exponent;
              return shape;
          }()) {}
    /// Any transition shape (eq. 6, or an abrupt step into a late-wood band).
    explicit RingProfile(const LateWoodShape& shape);

    /// E at growth time T (unfiltered), from a table: within 1e-5 of sin^n, without the
    /// sin and pow that would otherwise dominate shading.
    double lateWood(double T) const;
    /// The mean of E over [T - width/2, T + width/2] (width in years; <= 0 = unfiltered).
    double filtered(double T, double width) const;
    /// d/dT of filtered(T, width): the exact slope of the box-filtered profile, finite even
    /// across the sharp late-to-early-wood step at each ring boundary when width > 0.
    double filteredSlope(double T, double width) const;
    /// Mean of E over a whole ring.
    double ringMean() const { return cumulative_.back(); }

private:
    /// Integral of E from 0 to T (T may span many rings).
    double integral(double T) const;

    LateWoodShape shape_;
    std::vector<double> values_;      ///< E(i / N), i = 0..N (the last one the limit from below)
    std::vector<double> cumulative_;  ///< integral of E over [0, i / N], i = 0..N
};

}  // namespace nenrin
