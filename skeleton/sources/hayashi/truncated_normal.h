#pragma once
/// A normal distribution cut to [lo, hi], set up from the moments a paper reports for its
/// sample (mean, standard deviation, minimum, maximum) rather than from its own parameters.
///
/// Hayashi & Takahashi give the angle between consecutive first-order branches as "mean 173,
/// sd 73, min 33, max 293 degrees": a truncated normal on [33, 293] whose *truncated* mean and
/// sd are those numbers has a location and scale that differ from them (truncation pulls the
/// mean and shrinks the sd), so they are solved for here.

#include "util/hash.h"

namespace nenrin {

class TruncatedNormal {
public:
    /// The distribution on [lo, hi] whose mean is `mean` and whose sd is `sd` (lo < mean < hi,
    /// sd > 0). An sd wider than any truncated normal with that mean can have (the sample is
    /// nearly uniform) gets the widest one the solver reaches, 20 ranges wide.
    static TruncatedNormal fromMoments(double mean, double sd, double lo, double hi);

    double location() const { return mu_; }
    double scale() const { return sigma_; }
    double lo() const { return lo_; }
    double hi() const { return hi_; }
    /// The mean and sd of the truncated distribution (closed form).
    double mean() const;
    double sd() const;

    /// One draw by rejection from whichever proposal (the normal itself, or uniform on
    /// [lo, hi]) accepts more often; exact, and a fixed function of the generator's state.
    double draw(SplitMix& rng) const;

private:
    TruncatedNormal(double mu, double sigma, double lo, double hi);
    double mu_, sigma_, lo_, hi_;
    bool uniformProposal_;
};

}  // namespace nenrin
