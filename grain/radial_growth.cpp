#include "grain/radial_growth.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace nenrin {

RadialGrowth::RadialGrowth(const std::vector<double>& widths, double referenceSpeed)
    : widths_(widths), referenceSpeed_(referenceSpeed) {
    if (!(referenceSpeed > 0)) throw std::invalid_argument("RadialGrowth: Sb must be > 0");
    sums_.push_back(0);
    for (double w : widths_) {
        if (!(w >= 0)) throw std::invalid_argument("RadialGrowth: ring widths must be >= 0");
        sums_.push_back(sums_.back() + w);
        maxSpeedRatio_ = std::max(maxSpeedRatio_, w / referenceSpeed);
    }
    // Before the first and after the last year the nearest non-zero ring width continues.
    for (double w : widths_)
        if (w > 0) {
            if (!(firstWidth_ > 0)) firstWidth_ = w;
            lastWidth_ = w;
        }
    if (!(lastWidth_ > 0)) throw std::invalid_argument("RadialGrowth: no ring has a width");
}

double RadialGrowth::cumulative(double t) const {
    // NaN goes here too: it has no year to index.
    if (!(t > 0)) return t * firstWidth_;
    double years = static_cast<double>(widths_.size());
    if (t >= years) return sums_.back() + (t - years) * lastWidth_;
    size_t k = static_cast<size_t>(t);
    return sums_[k] + (t - static_cast<double>(k)) * widths_[k];
}

double RadialGrowth::inverseCumulative(double c) const {
    if (!(c > 0)) return c / firstWidth_;  // NaN too
    if (c >= sums_.back())
        return static_cast<double>(widths_.size()) + (c - sums_.back()) / lastWidth_;
    // The year whose ring contains c: sums_[k] <= c < sums_[k + 1], so w_k > 0 (a zero-width
    // year has sums_[k] = sums_[k + 1] and is stepped over: its ring merges with the next).
    size_t k =
        static_cast<size_t>(std::upper_bound(sums_.begin(), sums_.end(), c) - sums_.begin()) - 1;
    return static_cast<double>(k) + (c - sums_[k]) / widths_[k];
}

}  // namespace nenrin
