#pragma once
/// When in each year the late wood begins. A grain's transition shape puts the late-wood
/// onset (E = 1/2) at one phase of every ring, 1 - S; measured earlywood/latewood pairs
/// (skeleton latewood_shares) and the stochastic ring model give each year k its own share
/// s_k. The timing maps a growth time T to the time T' at which the grain's profile is read:
/// within ring k, phase u goes to u (1 - S) / (1 - s_k) before the onset and linearly onto the
/// late-wood part after it, so E crosses 1/2 at 1 - s_k and ring boundaries stay in place.

#include <vector>

namespace nenrin {

class LatewoodTiming {
public:
    LatewoodTiming() = default;  ///< no yearly shares: T' = T
    /// `shares` per year (each in (0, 1)); `profileShare` S, the share the profile itself has.
    LatewoodTiming(std::vector<double> shares, double profileShare);

    bool empty() const { return shares_.empty(); }
    /// T' for growth time T; `slope` (if given) receives dT'/dT there.
    double profileTime(double T, double* slope = nullptr) const;
    double share(double year) const;

private:
    std::vector<double> shares_;
    double profileShare_ = 0.3;
};

}  // namespace nenrin
