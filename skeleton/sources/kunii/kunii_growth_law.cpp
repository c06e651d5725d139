#include "skeleton/sources/kunii/kunii_growth_law.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace nenrin {

namespace {

using Quartic = std::array<double, 5>;  // coefficients of g^0 .. g^4

/// Coefficients of a (g + b) (c (g - d)^2 + e) (I - f g).
Quartic linearisedPolynomial(const KuniiGrowthLaw& L, double I) {
    // (g + b) (I - f g) = -f g^2 + (I - f b) g + b I
    std::array<double, 3> lin{L.b * I, I - L.f * L.b, -L.f};
    // c (g - d)^2 + e = c g^2 - 2 c d g + (c d^2 + e)
    std::array<double, 3> quad{L.c * L.d * L.d + L.e, -2 * L.c * L.d, L.c};
    Quartic out{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) out[static_cast<size_t>(i + j)] += L.a * lin[i] * quad[j];
    return out;
}

/// Coefficients of P(G + s) from those of P(g) (Taylor shift).
Quartic shifted(const Quartic& p, double s) {
    constexpr int binom[5][5] = {
        {1, 0, 0, 0, 0}, {1, 1, 0, 0, 0}, {1, 2, 1, 0, 0}, {1, 3, 3, 1, 0}, {1, 4, 6, 4, 1}};
    Quartic out{};
    for (int k = 0; k < 5; ++k)
        for (int j = 0; j <= k; ++j)
            out[static_cast<size_t>(j)] +=
                p[static_cast<size_t>(k)] * binom[k][j] * std::pow(s, k - j);
    return out;
}

}  // namespace

double relativeGrowthRate(const KuniiGrowthLaw& L, double g, double I) {
    double steepness = L.c * (g - L.d) * (g - L.d) + L.e;
    return L.a * (g + L.b) * (1.0 - std::exp(-steepness * (I - L.f * g)));
}

double compensationIrradiance(const KuniiGrowthLaw& L, double g) { return L.f * g; }

double compensationSlope(const KuniiGrowthLaw& L, double g) {
    return L.a * (g + L.b) * (L.c * (g - L.d) * (g - L.d) + L.e);
}

double linearisedGrowthRate(const KuniiGrowthLaw& L, double g, double I) {
    return L.a * (g + L.b) * (L.c * (g - L.d) * (g - L.d) + L.e) * (I - L.f * g);
}

CuspQuartic cuspQuartic(const KuniiGrowthLaw& L, double I) {
    CuspQuartic q;
    q.shift = (I + L.f * (2 * L.d - L.b)) / (4 * L.f);
    Quartic G = shifted(linearisedPolynomial(L, I), q.shift);
    q.alpha = -G[4];  // = a c f
    q.cubicResidue = G[3];
    q.p = G[2] / q.alpha;
    q.q = G[1] / q.alpha;
    q.r = -G[0] / q.alpha;
    return q;
}

std::vector<double> stationarySpecies(const KuniiGrowthLaw& L, double I) {
    CuspQuartic c = cuspQuartic(L, I);
    // 4 G^3 - 2 p G - q = 0  <=>  G^3 + P G + Q = 0
    double P = -c.p / 2, Q = -c.q / 4;
    std::vector<double> roots;
    double disc = 4 * P * P * P + 27 * Q * Q;
    if (disc < 0) {
        // Three real roots (trigonometric form).
        double m = 2 * std::sqrt(-P / 3);
        double theta = std::acos(std::clamp(3 * Q / (P * m), -1.0, 1.0)) / 3;
        for (int k = 0; k < 3; ++k)
            roots.push_back(m * std::cos(theta - 2 * std::numbers::pi * k / 3) + c.shift);
        std::sort(roots.begin(), roots.end());
    } else {
        double s = std::sqrt(disc / 108);
        roots.push_back(std::cbrt(-Q / 2 + s) + std::cbrt(-Q / 2 - s) + c.shift);
    }
    return roots;
}

bool isBistable(const KuniiGrowthLaw& L, double I) {
    CuspQuartic c = cuspQuartic(L, I);
    return 8 * c.p * c.p * c.p > 27 * c.q * c.q;
}

double followBestSpecies(const KuniiGrowthLaw& L, double I, double gStart, double gMin,
                         double gMax) {
    double g = std::clamp(gStart, gMin, gMax);
    double best = relativeGrowthRate(L, g, I);
    // Pattern search: step while it improves, halve the step when neither side does. It
    // stays on the hill it starts on, which is the point of following.
    for (double step = 0.01 * (gMax - gMin); step > 1e-9 * (gMax - gMin);) {
        double up = std::min(g + step, gMax), down = std::max(g - step, gMin);
        double rUp = relativeGrowthRate(L, up, I), rDown = relativeGrowthRate(L, down, I);
        if (rUp > best && rUp >= rDown) {
            g = up;
            best = rUp;
        } else if (rDown > best) {
            g = down;
            best = rDown;
        } else {
            step /= 2;
        }
    }
    return g;
}

std::vector<double> sweepBestSpecies(const KuniiGrowthLaw& L, const std::vector<double>& Is,
                                     double gStart, double gMin, double gMax) {
    std::vector<double> out;
    double g = gStart;
    for (double I : Is) {
        g = followBestSpecies(L, I, g, gMin, gMax);
        out.push_back(g);
    }
    return out;
}

double globallyBestSpecies(const KuniiGrowthLaw& L, double I, double gMin, double gMax,
                           int samples) {
    double bestG = gMin, best = relativeGrowthRate(L, gMin, I);
    for (int i = 1; i < samples; ++i) {
        double g = gMin + (gMax - gMin) * i / (samples - 1);
        double r = relativeGrowthRate(L, g, I);
        if (r > best) {
            best = r;
            bestG = g;
        }
    }
    return bestG;
}

}  // namespace nenrin
