#include "fit/profile_sharpening.h"

#include <algorithm>
#include <cmath>

namespace nenrin {

namespace {

/// Richardson-Lucy iterations: enough to restore a line a few samples wide, few enough that the
/// noise of the measured profile is not raised into ripples.
constexpr int kIterations = 25;
/// Blurs wider than this (ring phase) are not undone: the profile then carries little of the
/// ring's own shape, and the deconvolution would invent it.
constexpr double kLargestBlur = 0.08;

/// Periodic convolution with a Gaussian of `sigma` samples.
std::vector<double> convolve(const std::vector<double>& v, double sigma) {
    const int n = static_cast<int>(v.size());
    const int half = static_cast<int>(std::ceil(4 * sigma));
    std::vector<double> kernel(size_t(2 * half + 1));
    double sum = 0;
    for (int k = -half; k <= half; ++k)
        sum += kernel[size_t(k + half)] = std::exp(-0.5 * (k / sigma) * (k / sigma));
    std::vector<double> out(v.size(), 0);
    for (int i = 0; i < n; ++i) {
        double s = 0;
        for (int k = -half; k <= half; ++k)
            s += kernel[size_t(k + half)] * v[size_t(((i + k) % n + n) % n)];
        out[size_t(i)] = s / sum;
    }
    return out;
}

/// The standard deviation (samples) of the profile's steepest fall: the spread of its
/// successive differences over the run of falling samples around the steepest one, less the
/// spread a step falling between two samples has (1/12 of a sample squared). 0 if there is no
/// clear fall.
double fallWidth(const std::vector<double>& v) {
    const int n = static_cast<int>(v.size());
    auto fall = [&](int i) { return v[size_t(i % n)] - v[size_t((i + 1) % n)]; };  // > 0 falling
    int steepest = 0;
    for (int i = 1; i < n; ++i)
        if (fall(i) > fall(steepest)) steepest = i;
    double weight = 0, first = 0, second = 0;
    // The run: falling samples on either side, up to half a ring.
    int from = steepest, to = steepest;
    while (from > steepest - n / 2 && fall((from - 1 + n) % n) > 0) --from;
    while (to < steepest + n / 2 && fall((to + 1) % n) > 0) ++to;
    for (int i = from; i <= to; ++i) {
        const double w = fall((i + n) % n);
        weight += w, first += w * i, second += w * i * i;
    }
    if (weight < 0.1) return 0;
    const double mean = first / weight;
    return std::sqrt(std::max(0.0, second / weight - mean * mean - 1.0 / 12));
}

}  // namespace

std::vector<double> blurLateWoodProfile(const std::vector<double>& profile, double blur) {
    const double sigma = blur * double(profile.size());
    return sigma > 0 ? convolve(profile, sigma) : profile;
}

SharpenedProfile sharpenLateWoodProfile(const std::vector<double>& profile) {
    SharpenedProfile out{profile, 0};
    const double n = double(profile.size());
    const double sigma = profile.size() >= 8 ? fallWidth(profile) : 0;
    if (sigma < 0.5 || sigma > kLargestBlur * n) return out;
    out.blur = sigma / n;
    // Richardson-Lucy: the estimate times the blurred ratio of the measured to its own blur
    // (the kernel is symmetric); E is a share, so it is held at most 1.
    std::vector<double>& e = out.profile;
    for (double& x : e) x = std::clamp(x, 1e-6, 1.0);
    for (int it = 0; it < kIterations; ++it) {
        const std::vector<double> blurred = convolve(e, sigma);
        std::vector<double> ratio(e.size());
        for (size_t i = 0; i < e.size(); ++i)
            ratio[i] = std::clamp(profile[i], 0.0, 1.0) / std::max(blurred[i], 1e-9);
        const std::vector<double> correction = convolve(ratio, sigma);
        for (size_t i = 0; i < e.size(); ++i) e[i] = std::min(1.0, e[i] * correction[i]);
    }
    return out;
}

}  // namespace nenrin
