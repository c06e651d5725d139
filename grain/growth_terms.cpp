#include "grain/growth_terms.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "util/hash.h"

namespace nenrin {

namespace {

/// x less the nearest multiple k pi of pi (k's parity in `odd`): in [-pi/2, pi/2].
inline double reduceByPi(double x, bool& odd) {
    constexpr double kInvPi = 1 / std::numbers::pi;
    constexpr double kPiHi = 3.141592653589793116;  // pi split in two for an exact reduction
    constexpr double kPiLo = 1.2246467991473532e-16;
    const double y = x * kInvPi;
    // The nearest integer by adding and taking away 1.5 x 2^52 (the baseline x86-64 build has
    // no rounding instruction, and floor was a fifth of the sines' cost); floor beyond 2^51.
    constexpr double kRound = 0x1.8p52;
    const double k = std::abs(y) < 0x1p51 ? (y + kRound) - kRound : std::floor(y + 0.5);
    odd = std::abs(k) < 0x1p62 && (static_cast<long long>(k) & 1);
    return (x - k * kPiHi) - k * kPiLo;
}

/// sin(x) to 6e-8 (Taylor to x^11 on [-pi/2, pi/2] after reducing by multiples of pi), for
/// the sway waves: they are a perturbation of a few millimetres, evaluated several times per
/// field sample, and libm's sin was the largest single cost of shading wood. The reduction is
/// exact at the seams (the polynomial is odd), so the waves stay continuous.
inline double swaySin(double x) {
    bool odd;
    double r = reduceByPi(x, odd);
    double r2 = r * r;
    double s =
        r * (1 + r2 * (-1.0 / 6 +
                       r2 * (1.0 / 120 +
                             r2 * (-1.0 / 5040 + r2 * (1.0 / 362880 + r2 * (-1.0 / 39916800))))));
    return odd ? -s : s;
}

struct SinCos {
    double sin, cos;
};

/// sin(x) and cos(x) to 7e-10 with swaySin's reduction (Taylor to x^13 and x^14), for the
/// phases of the radial factor's harmonics.
inline SinCos swaySinCos(double x) {
    bool odd;
    double r = reduceByPi(x, odd);
    double r2 = r * r;
    double s =
        r * (1 + r2 * (-1.0 / 6 +
                       r2 * (1.0 / 120 +
                             r2 * (-1.0 / 5040 + r2 * (1.0 / 362880 + r2 * (-1.0 / 39916800 +
                                                                            r2 / 6227020800.0))))));
    double c =
        1 + r2 * (-1.0 / 2 +
                  r2 * (1.0 / 24 +
                        r2 * (-1.0 / 720 + r2 * (1.0 / 40320 + r2 * (-1.0 / 3628800 +
                                                                     r2 * (1.0 / 479001600 -
                                                                           r2 / 87178291200.0))))));
    return odd ? SinCos{-s, -c} : SinCos{s, c};
}

}  // namespace

double lateWoodFraction(double growthTime, double exponent) {
    double u = growthTime - std::floor(growthTime);
    double s = std::sin(0.5 * std::numbers::pi * u);
    return std::pow(s, exponent);
}

double lateWoodFraction(double growthTime, const LateWoodShape& shape) {
    double u = growthTime - std::floor(growthTime);
    if (shape.table.size() >= 2) {
        double x = u * double(shape.table.size() - 1);
        size_t i = std::min(static_cast<size_t>(x), shape.table.size() - 2);
        return shape.table[i] + (x - double(i)) * (shape.table[i + 1] - shape.table[i]);
    }
    if (shape.share <= 0) return lateWoodFraction(growthTime, shape.exponent);
    double start = 1 - shape.share;
    const double step =
        smoothstep(start - 0.5 * shape.transition, start + 0.5 * shape.transition, u);
    if (shape.earlyRise == 0 && shape.lateRamp == 0) return step;
    const double x = std::min(u / start, 1.0);
    const double early = shape.earlyRise * x * x;
    const double ramp = 1 - shape.lateRamp * (1 - std::clamp((u - start) / shape.share, 0.0, 1.0));
    return early + (1 - early) * step * ramp;
}

SwayWaves makeSwayWaves(const SwayParams& sway) {
    SwayWaves w;
    w.amplitude = sway.amplitude;
    w.radialJitter = sway.radialJitter;
    const double k = 2 * std::numbers::pi / sway.wavelength;
    for (int axis = 0; axis < 3; ++axis)
        for (int i = 0; i < SwayWaves::kWaves; ++i) {
            // Random directions; harmonic i has about 1/(i+1) of the given wavelength.
            uint64_t key = static_cast<uint64_t>(axis * SwayWaves::kWaves + i);
            double theta = 2 * std::numbers::pi * uniform01(sway.seed, key, 1);
            double phi = std::acos(2 * uniform01(sway.seed, key, 2) - 1);
            double scale = 0.6 + 0.8 * uniform01(sway.seed, key, 3);
            Vec3 dir{std::sin(phi) * std::cos(theta), std::sin(phi) * std::sin(theta),
                     std::cos(phi)};
            w.direction[axis][i] = dir * (k * scale * (i + 1));
            w.phase[axis][i] = 2 * std::numbers::pi * uniform01(sway.seed, key, 4);
        }
    for (int i = 0; i < SwayWaves::kWaves; ++i) {
        w.radialPhase[i] = 2 * std::numbers::pi * uniform01(sway.seed, 100 + i, 0);
        w.radialDrift[i] = 0.4 * (uniform01(sway.seed, 100 + i, 1) - 0.5);
    }
    return w;
}

Vec3 swayDisplacement(const Vec3& p, const SwayWaves& w) {
    if (w.amplitude == 0) return {};
    // Harmonic i has weight 1/(i+1); the weights sum to `norm`, so |component| <= amplitude.
    constexpr double norm = 1.0 + 1.0 / 2 + 1.0 / 3;
    double c[3];
    for (int axis = 0; axis < 3; ++axis) {
        double sum = 0;
        for (int i = 0; i < SwayWaves::kWaves; ++i)
            sum += swaySin(dot(w.direction[axis][i], p) + w.phase[axis][i]) / (i + 1);
        c[axis] = sum / norm;
    }
    return Vec3{c[0], c[1], c[2]} * w.amplitude;
}

SwayFrame swayFrame(const Vec3& axis) {
    // Azimuth about the axis, measured from world X projected onto the normal plane (world Y
    // for axes close to X), so it varies smoothly along a smoothly bending axis.
    Vec3 ref = std::abs(axis.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    Vec3 u = normalize(ref - axis * dot(ref, axis));
    return {u, cross(axis, u)};
}

double swayRadialFactor(const Vec3& outwardNormal, const SwayFrame& frame, double elongationYears,
                        const SwayWaves& w) {
    if (w.radialJitter == 0) return 1;
    constexpr double norm = 1.0 + 1.0 / 2 + 1.0 / 3;
    const double x = dot(outwardNormal, frame.u), y = dot(outwardNormal, frame.v);
    const double r2 = x * x + y * y;
    double h = 0;
    if (!(r2 > 0)) {
        // The normal along the axis: no azimuth but atan2's for a zero vector.
        const double az = std::atan2(y, x);
        for (int i = 0; i < SwayWaves::kWaves; ++i)
            h += swaySin((i + 1) * az + w.radialPhase[i] + w.radialDrift[i] * elongationYears) /
                 (i + 1);
        return 1 + w.radialJitter * h / norm;
    }
    // sin(k az + psi_k) = sin(k az) cos(psi_k) + cos(k az) sin(psi_k), the harmonics of az
    // from its cosine and sine by the angle sums: no atan2, one sine and cosine per harmonic.
    const double inv = 1 / std::sqrt(r2);
    const double c1 = x * inv, s1 = y * inv;
    const double c2 = c1 * c1 - s1 * s1, s2 = 2 * s1 * c1;
    const double ck[SwayWaves::kWaves] = {c1, c2, c1 * c2 - s1 * s2};
    const double sk[SwayWaves::kWaves] = {s1, s2, s1 * c2 + c1 * s2};
    for (int i = 0; i < SwayWaves::kWaves; ++i) {
        const SinCos psi = swaySinCos(w.radialPhase[i] + w.radialDrift[i] * elongationYears);
        h += (sk[i] * psi.cos + ck[i] * psi.sin) / (i + 1);
    }
    return 1 + w.radialJitter * h / norm;
}

double swayRadialFactor(const Vec3& outwardNormal, const Vec3& axis, double elongationYears,
                        const SwayWaves& w) {
    return swayRadialFactor(outwardNormal, swayFrame(axis), elongationYears, w);
}

double microStructure(const Vec3& p, double cellSize, uint64_t seed) {
    constexpr int kSize = 16;
    // The cell index modulo kSize, taken in doubles: a far point (1e30 m in a host's scene)
    // has no integer cell index.
    auto cell = [&](double c) {
        double i = std::fmod(std::floor(c / cellSize), kSize);
        if (!std::isfinite(i)) return uint64_t{0};
        return static_cast<uint64_t>(i < 0 ? i + kSize : i);
    };
    uint64_t ix = cell(p.x), iy = cell(p.y);
    return 2 * uniform01(seed, ix * kSize + iy) - 1;
}

}  // namespace nenrin
