#pragma once
/// A tree's recorded radial growth (Skeleton::ringWidths): the thickening part of the growth
/// time follows the years the tree actually lived instead of a constant speed Sb.
///
/// With constant speed, a point D metres (trunk-equivalent) out from an axis point born at Ta is
/// reached at Ta + D / Sb. With yearly ring widths w_k the cambium's cumulative growth is
/// C(t) = w_0 + ... + w_{k-1} + (t - k) w_k for k = floor(t), so the point is reached when
/// C(T) = C(Ta) + D: T = C^-1(C(Ta) + D). Every other term (gamma, taper, direction, jitter,
/// age warp) still scales D exactly as before, so the grain's Sb is the unit in which they are
/// expressed: D = Sb x (their constant-speed thickening years). Before year 0 the first width
/// applies, after the last year the last width continues (the nearest non-zero ones).

#include <vector>

namespace nenrin {

class RadialGrowth {
public:
    RadialGrowth() = default;
    /// `widths` in m/year (>= 0, some > 0; a 0 is a locally absent ring that merges with the
    /// next); `referenceSpeed` = the grain's Sb.
    RadialGrowth(const std::vector<double>& widths, double referenceSpeed);

    bool empty() const { return widths_.empty(); }
    /// The time at which growth started at `birth` reaches the point that constant speed Sb
    /// would reach after `constantYears`.
    double arrivalTime(double birth, double constantYears) const {
        return inverseCumulative(cumulative(birth) + constantYears * referenceSpeed_);
    }
    /// Largest width / Sb (>= 1): how much faster than Sb the cambium ever grows.
    double maxSpeedRatio() const { return maxSpeedRatio_; }

    double cumulative(double t) const;
    double inverseCumulative(double c) const;

private:
    std::vector<double> widths_;
    std::vector<double> sums_;  ///< sums_[k] = C(k), k = 0 … years
    double referenceSpeed_ = 1;
    double firstWidth_ = 0, lastWidth_ = 0;  ///< the first and last non-zero widths
    double maxSpeedRatio_ = 1;
};

}  // namespace nenrin
