#include "shader/colour_line.h"

#include <algorithm>
#include <cmath>

namespace nenrin {

Rgb woodColourLine(const Rgb& earlyWood, const Rgb& lateWood) {
    const Rgb grey{1, 1, 1};
    auto logRatio = [](double late, double early) {
        return late > 0 && early > 0 ? std::log(late / early) : 0.0;
    };
    const Rgb d{logRatio(lateWood.r, earlyWood.r), logRatio(lateWood.g, earlyWood.g),
                logRatio(lateWood.b, earlyWood.b)};
    // The luminance-weighted mean: the change in ln(luminance) near a grey wood.
    const double mean = luminance(d);
    if (!(std::abs(mean) >= 0.05)) return grey;
    auto channel = [&](double x) { return std::clamp(x / mean, 0.5, 2.0); };
    return {channel(d.r), channel(d.g), channel(d.b)};
}

Rgb alongColourLine(const Rgb& albedo, const AnatomySample& anatomy, const Rgb& line) {
    if (line.r == 1 && line.g == 1 && line.b == 1) return multiply(albedo, anatomy.filter());
    const double b = anatomy.brightness;
    const Rgb& after = anatomy.pores;
    const double y = luminance(albedo), yLine = luminance(multiply(albedo, line));
    const double s = yLine > 0 ? y / yLine : 1;
    auto factor = [&](double c, double l, double a) {
        return c * std::max(0.0, (1 + (b - 1) * s * l) * a);
    };
    return {factor(albedo.r, line.r, after.r), factor(albedo.g, line.g, after.g),
            factor(albedo.b, line.b, after.b)};
}

}  // namespace nenrin
