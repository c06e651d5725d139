#pragma once
/// CIELAB (D65) exactly as the team's photo-stats script computes it: a 4-digit sRGB -> XYZ
/// matrix and the 0.008856 / 7.787 form of f(t). grain/cielab.h is the same space with exact
/// constants; they differ by ~0.01 dE, but the statistics promise the script's numbers.

#include <algorithm>
#include <array>
#include <cmath>

namespace nenrin {

/// L*, a*, b* of a scene-linear sRGB (Rec. 709) colour.
inline std::array<double, 3> photoLabFromLinear(double r, double g, double b) {
    const double x = (0.4124 * r + 0.3576 * g + 0.1805 * b) / 0.95047;
    const double y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
    const double z = (0.0193 * r + 0.1192 * g + 0.9505 * b) / 1.08883;
    auto f = [](double t) {
        return t > 0.008856 ? std::cbrt(std::max(t, 0.0)) : 7.787 * t + 16.0 / 116.0;
    };
    const double fx = f(x), fy = f(y), fz = f(z);
    return {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
}

}  // namespace nenrin
