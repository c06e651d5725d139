#include "fit/anatomy_tone.h"

#include <algorithm>
#include <cmath>

#include "grain/rgb.h"

namespace nenrin {

namespace {

constexpr int kMinPixels = 50;

Rgb rgbOf(const nlohmann::json& c) {
    return {c[0].get<double>(), c[1].get<double>(), c[2].get<double>()};
}

/// The bakes' mean luminance at each of `n` ring phases (the nearest profile sample to
/// frac(T)), over the fitted faces' stem wood; the pixel counts in `count`.
std::vector<double> phaseLuminance(std::span<const FaceFigures> faces, size_t n,
                                   std::vector<int>& count) {
    std::vector<double> sum(n, 0);
    count.assign(n, 0);
    for (const FaceFigures& f : faces) {
        if (f.heldOut) continue;
        for (int y = 0; y < f.bake.height; ++y)
            for (int x = 0; x < f.bake.width; ++x) {
                const float* v = f.bake.at(x, y);
                if (!(v[3] > 0) || v[5] > 0.25f || !std::isfinite(v[4])) continue;
                const double phase = double(v[4]) - std::floor(double(v[4]));
                const size_t k = std::min(n - 1, size_t(std::lround(phase * double(n - 1))));
                sum[k] += luminance(Rgb{v[0], v[1], v[2]});
                ++count[k];
            }
    }
    for (size_t k = 0; k < n; ++k) sum[k] /= std::max(1, count[k]);
    return sum;
}

}  // namespace

std::vector<double> anatomyTone(std::span<const FaceFigures> withAnatomy,
                                std::span<const FaceFigures> without, size_t n) {
    std::vector<double> tone(n, 1.0);
    if (n < 2) return tone;
    std::vector<int> countWith, countWithout;
    const std::vector<double> with = phaseLuminance(withAnatomy, n, countWith);
    const std::vector<double> plain = phaseLuminance(without, n, countWithout);
    // Phases enough pixels of both fall in: their ratio, over its mean; the rest stay 1.
    std::vector<size_t> measured;
    double sum = 0;
    for (size_t k = 0; k < n; ++k)
        if (countWith[k] >= kMinPixels && countWithout[k] >= kMinPixels && plain[k] > 0 &&
            with[k] > 0) {
            measured.push_back(k);
            sum += with[k] / plain[k];
        }
    const double mean = sum / double(std::max<size_t>(1, measured.size()));
    for (size_t k : measured) tone[k] = with[k] / plain[k] / mean;
    return tone;
}

bool removeAnatomyTone(nlohmann::json& grain, std::span<const double> tone) {
    if (!grain.contains("colour")) return false;
    nlohmann::json& colour = grain["colour"];
    if (!colour.contains("late_wood_profile") || !colour.contains("early_wood") ||
        !colour.contains("late_wood"))
        return false;
    nlohmann::json& profile = colour["late_wood_profile"];
    if (profile.size() != tone.size()) return false;
    const double early = luminance(rgbOf(colour["early_wood"])),
                 late = luminance(rgbOf(colour["late_wood"]));
    if (!(std::abs(late - early) > 0.01 * std::max(early, late))) return false;
    for (size_t k = 0; k < tone.size(); ++k) {
        const double e = profile[k].get<double>();
        const double wanted = (early + e * (late - early)) / tone[k];
        profile[k] =
            std::round(1e3 * std::clamp((wanted - early) / (late - early), 0.0, 1.0)) / 1e3;
    }
    return true;
}

}  // namespace nenrin
