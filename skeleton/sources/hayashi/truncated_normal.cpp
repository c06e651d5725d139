#include "skeleton/sources/hayashi/truncated_normal.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "util/random_draws.h"

namespace nenrin {

namespace {

double pdf(double x) { return std::exp(-0.5 * x * x) / std::sqrt(2 * std::numbers::pi); }

/// Phi(b) - Phi(a) without cancellation in the far tails.
double massBetween(double a, double b) {
    if (a > 0)
        return 0.5 * (std::erfc(a / std::numbers::sqrt2) - std::erfc(b / std::numbers::sqrt2));
    if (b < 0)
        return 0.5 * (std::erfc(-b / std::numbers::sqrt2) - std::erfc(-a / std::numbers::sqrt2));
    return 1 - 0.5 * std::erfc(-a / std::numbers::sqrt2) - 0.5 * std::erfc(b / std::numbers::sqrt2);
}

struct Moments {
    double mean, sd;
};

Moments truncatedMoments(double mu, double sigma, double lo, double hi) {
    double a = (lo - mu) / sigma, b = (hi - mu) / sigma;
    double z = massBetween(a, b);
    if (!(z > 1e-300)) return {std::clamp(mu, lo, hi), 0};
    double r = (pdf(a) - pdf(b)) / z;
    double var = 1 + (a * pdf(a) - b * pdf(b)) / z - r * r;
    return {mu + sigma * r, sigma * std::sqrt(std::max(var, 0.0))};
}

/// The location whose truncated mean is `mean`, for a given scale (the mean rises with mu).
double locationForMean(double mean, double sigma, double lo, double hi) {
    double range = hi - lo;
    double a = lo - 40 * range, b = hi + 40 * range;
    for (int i = 0; i < 200; ++i) {
        double m = 0.5 * (a + b);
        (truncatedMoments(m, sigma, lo, hi).mean < mean ? a : b) = m;
    }
    return 0.5 * (a + b);
}

}  // namespace

TruncatedNormal::TruncatedNormal(double mu, double sigma, double lo, double hi)
    : mu_(mu), sigma_(sigma), lo_(lo), hi_(hi) {
    // Acceptance of each proposal: the normal's mass in [lo, hi], or the mean height of the
    // density over [lo, hi] relative to its peak there.
    double z = massBetween((lo - mu) / sigma, (hi - mu) / sigma);
    double peak = pdf((std::clamp(mu, lo, hi) - mu) / sigma);
    double uniformAcceptance = z * sigma / ((hi - lo) * peak);
    uniformProposal_ = uniformAcceptance > z;
}

TruncatedNormal TruncatedNormal::fromMoments(double mean, double sd, double lo, double hi) {
    double range = hi - lo;
    // The truncated sd grows with the scale at a fixed mean: bisect on log(scale).
    double la = std::log(1e-4 * range), lb = std::log(20 * range);
    auto sdFor = [&](double logSigma) {
        double s = std::exp(logSigma);
        return truncatedMoments(locationForMean(mean, s, lo, hi), s, lo, hi).sd;
    };
    if (sdFor(lb) <= sd) {
        la = lb;
    } else {
        for (int i = 0; i < 100; ++i) {
            double m = 0.5 * (la + lb);
            (sdFor(m) < sd ? la : lb) = m;
        }
    }
    double sigma = std::exp(0.5 * (la + lb));
    return TruncatedNormal(locationForMean(mean, sigma, lo, hi), sigma, lo, hi);
}

double TruncatedNormal::mean() const { return truncatedMoments(mu_, sigma_, lo_, hi_).mean; }
double TruncatedNormal::sd() const { return truncatedMoments(mu_, sigma_, lo_, hi_).sd; }

double TruncatedNormal::draw(SplitMix& rng) const {
    double peakX = std::clamp(mu_, lo_, hi_);
    // Bounded so a pathological setting cannot hang; with the presets the first few succeed.
    for (int i = 0; i < 100000; ++i) {
        if (uniformProposal_) {
            double x = rng.uniform(lo_, hi_);
            double t = (x - mu_) / sigma_, t0 = (peakX - mu_) / sigma_;
            if (rng.uniform() < std::exp(-0.5 * (t * t - t0 * t0))) return x;
        } else {
            double x = drawNormal(rng, mu_, sigma_);
            if (x >= lo_ && x <= hi_) return x;
        }
    }
    return peakX;
}

}  // namespace nenrin
