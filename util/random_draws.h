#pragma once
/// Draws from the common distributions on top of SplitMix, written out so that a seed gives the
/// same numbers with every compiler and standard library (std:: distributions are
/// implementation-defined). Used by the tree generators and the MCMC sampler.

#include <cmath>
#include <numbers>

#include "util/hash.h"

namespace nenrin {

/// Standard normal (Box-Muller; two uniforms per draw, no cached pair: the draw count per
/// call is fixed, which keeps sequences easy to reason about).
inline double drawNormal(SplitMix& rng) {
    double u1 = 1.0 - rng.uniform();  // (0, 1]: log is finite
    double u2 = rng.uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

inline double drawNormal(SplitMix& rng, double mean, double sd) {
    return mean + sd * drawNormal(rng);
}

/// Normal(mean, sd) restricted to [lo, hi] by rejection (falls back to clamping after 64
/// tries, which only happens when [lo, hi] holds almost none of the mass).
inline double drawTruncatedNormal(SplitMix& rng, double mean, double sd, double lo, double hi) {
    for (int i = 0; i < 64; ++i) {
        double x = drawNormal(rng, mean, sd);
        if (x >= lo && x <= hi) return x;
    }
    return std::fmin(std::fmax(mean, lo), hi);
}

/// Gamma(shape, scale), mean shape * scale (Marsaglia & Tsang 2000; shape < 1 by the
/// u^(1/shape) boost).
inline double drawGamma(SplitMix& rng, double shape, double scale) {
    if (shape < 1.0) {
        double u = 1.0 - rng.uniform();
        return drawGamma(rng, shape + 1.0, scale) * std::pow(u, 1.0 / shape);
    }
    double d = shape - 1.0 / 3.0, c = 1.0 / std::sqrt(9.0 * d);
    for (;;) {
        double x = drawNormal(rng), v = 1.0 + c * x;
        if (v <= 0) continue;
        v = v * v * v;
        double u = 1.0 - rng.uniform();
        if (std::log(u) < 0.5 * x * x + d - d * v + d * std::log(v)) return d * v * scale;
    }
}

}  // namespace nenrin
