#include "fit/ring_starts.h"

#include <algorithm>
#include <cmath>

namespace nenrin {

namespace {

std::vector<double> gaussianSmooth(const std::vector<double>& v, double sigma) {
    const int reach = std::max(1, int(std::ceil(3 * sigma)));
    std::vector<double> kernel;
    double total = 0;
    for (int d = -reach; d <= reach; ++d) {
        kernel.push_back(std::exp(-0.5 * d * d / (sigma * sigma)));
        total += kernel.back();
    }
    const int n = int(v.size());
    std::vector<double> out(v.size());
    for (int i = 0; i < n; ++i) {
        double s = 0;
        for (int d = -reach; d <= reach; ++d)
            s += kernel[size_t(d + reach)] * v[size_t(std::clamp(i + d, 0, n - 1))];
        out[size_t(i)] = s / total;
    }
    return out;
}

/// The value below which a share `q` of `v` lies.
double quantile(std::vector<double> v, double q) {
    if (v.empty()) return 0;
    const size_t k = std::min(v.size() - 1, size_t(q * double(v.size())));
    std::nth_element(v.begin(), v.begin() + long(k), v.end());
    return v[k];
}

}  // namespace

std::vector<int> ringStarts(const std::vector<double>& lightness, double samplesPerPeriod) {
    const int n = int(lightness.size());
    if (n < 3) return {};
    // A ring's sharp edge stays, its texture goes: smoothed over a fifteenth of the period.
    const std::vector<double> smooth = gaussianSmooth(lightness, samplesPerPeriod / 15);
    std::vector<double> slope(lightness.size(), 0.0);
    for (int i = 1; i + 1 < n; ++i)
        slope[size_t(i)] = 0.5 * (smooth[size_t(i + 1)] - smooth[size_t(i - 1)]);
    std::vector<double> rises, falls;
    for (double s : slope) (s > 0 ? rises : falls).push_back(std::abs(s));
    const double rise = quantile(rises, 0.95), fall = quantile(falls, 0.95);
    const double sign = rise >= fall ? 1.0 : -1.0;
    const double threshold = 0.2 * std::max(rise, fall);
    // The steepest sample of each edge, edges at least half a period apart (a stronger edge
    // within that distance wins).
    const int gap = std::max(1, int(0.5 * samplesPerPeriod));
    std::vector<int> candidates;
    for (int i = 1; i + 1 < n; ++i) {
        const double s = sign * slope[size_t(i)];
        if (s > threshold && s >= sign * slope[size_t(i - 1)] && s >= sign * slope[size_t(i + 1)])
            candidates.push_back(i);
    }
    std::sort(candidates.begin(), candidates.end(), [&](int a, int b) {
        return sign * slope[size_t(a)] > sign * slope[size_t(b)] ||
               (slope[size_t(a)] == slope[size_t(b)] && a < b);
    });
    std::vector<int> starts;
    for (int c : candidates)
        if (std::all_of(starts.begin(), starts.end(),
                        [&](int s) { return std::abs(s - c) >= gap; }))
            starts.push_back(c);
    std::sort(starts.begin(), starts.end());
    return starts;
}

}  // namespace nenrin
