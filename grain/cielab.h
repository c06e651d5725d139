#pragma once
/// CIELAB (D65 white, 2° observer) from scene-linear sRGB (Rec. 709 primaries), the space in
/// which wood colour is measured and published: presets are checked against those tables in
/// ΔE*ab, and the end-grain term is stated in L* and a*.

#include <cmath>

#include "grain/rgb.h"

namespace nenrin {

struct Lab {
    double L = 0, a = 0, b = 0;
};

inline Lab labFromLinearSrgb(const Rgb& c) {
    const double x = (0.4124564 * c.r + 0.3575761 * c.g + 0.1804375 * c.b) / 0.95047;
    const double y = 0.2126729 * c.r + 0.7151522 * c.g + 0.0721750 * c.b;
    const double z = (0.0193339 * c.r + 0.1191920 * c.g + 0.9503041 * c.b) / 1.08883;
    auto f = [](double t) {
        return t > 216.0 / 24389.0 ? std::cbrt(t) : (24389.0 / 27.0 * t + 16) / 116;
    };
    const double fx = f(x), fy = f(y), fz = f(z);
    return {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
}

inline Rgb linearSrgbFromLab(const Lab& lab) {
    const double fy = (lab.L + 16) / 116, fx = fy + lab.a / 500, fz = fy - lab.b / 200;
    auto inv = [](double t) {
        return t * t * t > 216.0 / 24389.0 ? t * t * t : (116 * t - 16) * 27.0 / 24389.0;
    };
    const double x = 0.95047 * inv(fx), y = inv(fy), z = 1.08883 * inv(fz);
    return {3.2404542 * x - 1.5371385 * y - 0.4985314 * z,
            -0.9692660 * x + 1.8760108 * y + 0.0415560 * z,
            0.0556434 * x - 0.2040259 * y + 1.0572252 * z};
}

/// Scene-linear from an sRGB-encoded component (IEC 61966-2-1): how 8-bit photos are stored.
inline double linearFromSrgb(double v) {
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

inline Rgb linearFromSrgb(const Rgb& c) {
    return {linearFromSrgb(c.r), linearFromSrgb(c.g), linearFromSrgb(c.b)};
}

/// sRGB-encoded from a scene-linear component (IEC 61966-2-1), clamped to [0, 1].
inline double srgbFromLinear(double v) {
    v = v < 0 ? 0 : (v > 1 ? 1 : v);
    return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
}

/// ΔE*ab (CIE 1976): the distance in L*a*b*.
inline double deltaE(const Lab& p, const Lab& q) {
    return std::sqrt((p.L - q.L) * (p.L - q.L) + (p.a - q.a) * (p.a - q.a) +
                     (p.b - q.b) * (p.b - q.b));
}

}  // namespace nenrin
