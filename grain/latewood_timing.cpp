#include "grain/latewood_timing.h"

#include <algorithm>
#include <cmath>

namespace nenrin {

LatewoodTiming::LatewoodTiming(std::vector<double> shares, double profileShare)
    : shares_(std::move(shares)), profileShare_(std::clamp(profileShare, 0.01, 0.99)) {
    for (double& s : shares_) s = std::clamp(s, 0.01, 0.99);
}

double LatewoodTiming::share(double year) const {
    if (shares_.empty()) return profileShare_;
    // Clamped as a double: the T of a far point is no int.
    if (!(year > 0)) return shares_.front();
    if (year >= double(shares_.size() - 1)) return shares_.back();
    return shares_[size_t(year)];
}

double LatewoodTiming::profileTime(double T, double* slope) const {
    if (shares_.empty()) {
        if (slope) *slope = 1;
        return T;
    }
    const double k = std::floor(T), u = T - k;
    const double a = 1 - share(k), A = 1 - profileShare_;
    double v, d;
    if (u < a) {
        d = A / a;
        v = u * d;
    } else {
        d = profileShare_ / (1 - a);
        v = A + (u - a) * d;
    }
    if (slope) *slope = d;
    return k + std::min(v, std::nextafter(1.0, 0.0));
}

}  // namespace nenrin
