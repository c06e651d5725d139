#include "fit/knot_colour.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace nenrin {

namespace {

/// The knot colours' defaults (docs/grain-format.md) when the grain sets none.
constexpr double kDefaultDarkening = 0.25;
/// The total darkening is clamped at 0.95 (grain/knot_look.h).
constexpr double kMaxDarkening = 0.95;

}  // namespace

bool matchKnotColour(nlohmann::json& grain, std::span<const FaceFigures> faces) {
    std::array<double, 3> photo{}, baked{};
    int pixels = 0;
    for (const FaceFigures& f : faces) {
        if (f.heldOut) continue;
        for (int y = 0; y < f.bake.height; ++y)
            for (int x = 0; x < f.bake.width; ++x) {
                const float* v = f.bake.at(x, y);
                if (!isKnotWood(v)) continue;
                for (size_t c = 0; c < 3; ++c) {
                    photo[c] += f.photo[c].at(x, y);
                    baked[c] += std::max(0.0f, v[c]);
                }
                ++pixels;
            }
    }
    if (pixels < kMinKnotWoodPixels) return false;
    nlohmann::json& knots = grain["colour"]["knots"];
    if (!knots.is_object()) knots = nlohmann::json::object();
    const double darkening = knots.value("darkening", kDefaultDarkening);
    std::array<double, 3> tint = {1, 1, 1};
    if (knots.contains("tint"))
        for (size_t c = 0; c < 3; ++c) tint[c] = knots["tint"][c].get<double>();
    // The knot wood's colour is the stem's times (1 - darkening) times the tint: that
    // product, per channel, times the photo's over the bake's.
    std::array<double, 3> factor{};
    bool moved = false;
    for (size_t c = 0; c < 3; ++c) {
        const double ratio = baked[c] > 0 && photo[c] > 0 ? photo[c] / baked[c] : 1.0;
        if (std::abs(std::log(ratio)) > 0.01) moved = true;
        factor[c] = (1 - darkening) * tint[c] * ratio;
    }
    if (!moved) return false;
    const double brightest =
        std::clamp(*std::max_element(factor.begin(), factor.end()), 1 - kMaxDarkening, 1.0);
    auto rounded = [](double v) { return std::round(v * 1e4) / 1e4; };
    knots["darkening"] = rounded(1 - brightest);
    knots["tint"] = nlohmann::json::array();
    for (size_t c = 0; c < 3; ++c)
        knots["tint"].push_back(rounded(std::clamp(factor[c] / brightest, 0.0, 1.0)));
    return true;
}

}  // namespace nenrin
