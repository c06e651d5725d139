#include "fit/knot_halo.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "fit/end_grain_tint.h"

namespace nenrin {

namespace {

/// The probe's grey tint: a pixel of halo weight w bakes at 1 - (1 - kProbe) w of its colour.
constexpr double kProbe = 0.5;
/// The reaches tried (m across the stem, and the stretch along it): widths at the default
/// stretch first, then other stretches at the best width.
constexpr std::array<double, 5> kWidths = {0.003, 0.006, 0.010, 0.015, 0.022};
constexpr double kDefaultAxial = 3;
constexpr std::array<double, 2> kOtherAxials = {1.5, 6};
/// Pixels under this weight do not count in the tint's fit; fewer than this many halo pixels
/// over all fitted faces: no halo to fit.
constexpr double kMinWeight = 0.05;
constexpr int kMinHaloPixels = 200;

void setHalo(nlohmann::json& grain, const Rgb& tint, double width, double axial) {
    nlohmann::json& knots = grain["colour"]["knots"];
    if (!knots.is_object()) knots = nlohmann::json::object();
    knots["halo_tint"] = colourJson(tint);
    knots["halo_width"] = width;
    knots["halo_axial"] = axial;
}

struct Candidate {
    double width = 0, axial = 0;
    Rgb tint{1, 1, 1};
    double residual = std::numeric_limits<double>::infinity();
};

/// A fitted face's pixel the probe bake shows halo on: its weight, the colour without a halo
/// and the photographed one.
struct HaloPixel {
    double weight;
    std::array<double, 3> baked, photo;
};

std::vector<HaloPixel> haloPixels(const std::vector<FaceFigures>& plain,
                                  const std::vector<FaceFigures>& probe) {
    std::vector<HaloPixel> pixels;
    for (size_t f = 0; f < plain.size(); ++f) {
        if (plain[f].heldOut) continue;
        for (int y = 0; y < plain[f].bake.height; ++y)
            for (int x = 0; x < plain[f].bake.width; ++x) {
                const float *a = plain[f].bake.at(x, y), *b = probe[f].bake.at(x, y);
                const double sa = a[0] + a[1] + a[2], sb = b[0] + b[1] + b[2];
                if (!(sa > 1e-4)) continue;
                const double w = std::clamp((1 - sb / sa) / (1 - kProbe), 0.0, 1.0);
                if (w <= 0) continue;
                HaloPixel p{w, {}, {}};
                for (size_t ch = 0; ch < 3; ++ch)
                    p.baked[ch] = a[ch], p.photo[ch] = plain[f].photo[ch].at(x, y);
                pixels.push_back(p);
            }
    }
    return pixels;
}

/// The tint's least-squares fit for one reach, from the plain bakes and the probe's, and the
/// change in the residual it makes (sum of squares over the fitted faces' pixels, linear RGB).
void fitTint(const std::vector<FaceFigures>& plain, const std::vector<FaceFigures>& probe,
             Candidate& c) {
    const std::vector<HaloPixel> pixels = haloPixels(plain, probe);
    std::array<double, 3> num{}, den{};
    int counted = 0;
    for (const HaloPixel& p : pixels) {
        if (p.weight < kMinWeight) continue;
        ++counted;
        for (size_t ch = 0; ch < 3; ++ch) {
            const double wb = p.weight * p.baked[ch];
            num[ch] += wb * (p.photo[ch] - p.baked[ch]);
            den[ch] += wb * wb;
        }
    }
    if (counted < kMinHaloPixels) return;
    std::array<double, 3> t{};
    for (size_t ch = 0; ch < 3; ++ch)
        t[ch] = den[ch] > 0 ? std::clamp(1 + num[ch] / den[ch], 0.05, 1.0) : 1.0;
    c.tint = {t[0], t[1], t[2]};
    // (Elsewhere the bake is the same for every reach.)
    double residual = 0;
    for (const HaloPixel& p : pixels)
        for (size_t ch = 0; ch < 3; ++ch) {
            const double e = p.photo[ch] - p.baked[ch] * (1 + p.weight * (t[ch] - 1));
            const double e0 = p.photo[ch] - p.baked[ch];
            residual += e * e - e0 * e0;
        }
    c.residual = residual;
}

}  // namespace

HaloFit matchKnotHalo(nlohmann::json& grain, std::vector<FaceFigures>& faces,
                      const std::function<std::vector<FaceFigures>()>& rebake) {
    HaloFit out;
    const nlohmann::json before = grain;
    const std::vector<FaceFigures> plain = faces;
    Candidate best;
    auto tryReach = [&](double width, double axial) {
        setHalo(grain, {kProbe, kProbe, kProbe}, width, axial);
        const std::vector<FaceFigures> probe = rebake();
        ++out.bakes;
        Candidate c{width, axial};
        fitTint(plain, probe, c);
        if (c.residual < best.residual) best = c;
    };
    for (double width : kWidths) tryReach(width, kDefaultAxial);
    if (std::isfinite(best.residual)) {
        const double width = best.width;
        for (double axial : kOtherAxials) tryReach(width, axial);
    }
    grain = before;
    if (!std::isfinite(best.residual) || best.residual >= 0) return out;
    setHalo(grain, best.tint, best.width, best.axial);
    std::vector<FaceFigures> fitted = rebake();
    ++out.bakes;
    if (!(colourMisfit(fitted) < colourMisfit(plain))) {
        grain = before;
        return out;
    }
    out.kept = true;
    out.width = best.width;
    out.axial = best.axial;
    faces = std::move(fitted);
    return out;
}

}  // namespace nenrin
