#include "fit/end_grain_tint.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "grain/grain_params.h"

namespace nenrin {

namespace {

constexpr double kMaxColourDifference = 5;

bool isKind(FaceKind kind, std::span<const double> endWeights, size_t face) {
    return kind == FaceKind::Any || (endWeights[face] > 0.5) == (kind == FaceKind::End);
}

/// Per channel, the median over the fitted faces of `kind` of each pixel's photographed over
/// baked colour: the tint's measure, which a stain or a knot's halo covering part of one face
/// (the hinoki cube's face D) barely moves, where it would move a mean.
Rgb medianRatio(std::span<const FaceFigures> faces, FaceKind kind,
                std::span<const double> endWeights) {
    Rgb out{1, 1, 1};
    for (int c = 0; c < 3; ++c) {
        std::vector<float> ratios;
        for (size_t i = 0; i < faces.size(); ++i) {
            const FaceFigures& f = faces[i];
            if (f.heldOut || !isKind(kind, endWeights, i)) continue;
            for (int y = 0; y < f.bake.height; ++y)
                for (int x = 0; x < f.bake.width; ++x) {
                    const float baked = f.bake.at(x, y)[c], photo = f.photo[size_t(c)].at(x, y);
                    if (baked > 0 && photo > 0) ratios.push_back(photo / baked);
                }
        }
        if (ratios.empty()) continue;
        auto middle = ratios.begin() + std::ptrdiff_t(ratios.size() / 2);
        std::nth_element(ratios.begin(), middle, ratios.end());
        (c == 0 ? out.r : c == 1 ? out.g : out.b) = *middle;
    }
    return out;
}

/// The tint a grain's end grain has now: its own, or what darkening and redness make.
Rgb currentTint(const nlohmann::json& grain) {
    const ColourParams c = parseGrain(grain, "the fitted grain").colour;
    if (c.endGrainTint.r >= 0) return c.endGrainTint;
    return {1 - c.endGrainDarkening * (1 - c.endGrainRedness), 1 - c.endGrainDarkening,
            1 - c.endGrainDarkening};
}

}  // namespace

std::pair<int, double> colourMisfit(std::span<const FaceFigures> faces) {
    double sum = 0;
    int count = 0, over = 0;
    for (const FaceFigures& f : faces)
        if (!f.heldOut) sum += f.dE * f.dE, ++count, over += f.dE > kMaxColourDifference;
    return {over, count > 0 ? std::sqrt(sum / count) : 0};
}

double worstLog(const Rgb& ratio) {
    return std::max(
        {std::abs(std::log(ratio.r)), std::abs(std::log(ratio.g)), std::abs(std::log(ratio.b))});
}

nlohmann::json colourJson(const Rgb& c) {
    auto r = [](double v) { return std::round(v * 1e4) / 1e4; };
    return {r(c.r), r(c.g), r(c.b)};
}

void scaleWoodColours(nlohmann::json& grain, const Rgb& ratio) {
    for (const char* key : {"early_wood", "late_wood"}) {
        nlohmann::json& c = grain["colour"][key];
        c = colourJson({std::min(1.0, c[0].get<double>() * ratio.r),
                        std::min(1.0, c[1].get<double>() * ratio.g),
                        std::min(1.0, c[2].get<double>() * ratio.b)});
    }
}

Rgb colourRatio(std::span<const FaceFigures> faces, FaceKind kind,
                std::span<const double> endWeights) {
    double photo[3] = {0, 0, 0}, baked[3] = {0, 0, 0};
    for (size_t i = 0; i < faces.size(); ++i) {
        const FaceFigures& f = faces[i];
        if (f.heldOut || !isKind(kind, endWeights, i)) continue;
        for (int c = 0; c < 3; ++c)
            for (int y = 0; y < f.bake.height; ++y)
                for (int x = 0; x < f.bake.width; ++x) {
                    photo[c] += f.photo[size_t(c)].at(x, y);
                    baked[c] += f.bake.at(x, y)[c];
                }
    }
    auto ratio = [&](int c) { return baked[c] > 0 && photo[c] > 0 ? photo[c] / baked[c] : 1.0; };
    return {ratio(0), ratio(1), ratio(2)};
}

int matchEndGrainTint(nlohmann::json& grain, std::vector<FaceFigures>& faces,
                      std::span<const double> endWeights,
                      const std::function<std::vector<FaceFigures>()>& rebake, int rounds) {
    bool side = false, end = false;
    for (size_t i = 0; i < faces.size(); ++i)
        if (!faces[i].heldOut) (endWeights[i] > 0.5 ? end : side) = true;
    if (!side || !end) return 0;
    const nlohmann::json before = grain;
    const std::vector<FaceFigures> bakedBefore = faces;
    int bakes = 0;
    for (; bakes < rounds; ++bakes) {
        // The tint from the kinds' median ratios; the wood's colours from the side faces'
        // mean, as the colour calibration takes it.
        const Rgb sideRatio = colourRatio(faces, FaceKind::Side, endWeights);
        const Rgb sideMedian = medianRatio(faces, FaceKind::Side, endWeights);
        const Rgb endMedian = medianRatio(faces, FaceKind::End, endWeights);
        const Rgb relative{endMedian.r / sideMedian.r, endMedian.g / sideMedian.g,
                           endMedian.b / sideMedian.b};
        if (std::max(worstLog(sideRatio), worstLog(relative)) < 0.005) break;
        // (The tint a factor in [0.05, 1].)
        const Rgb tint = currentTint(grain);
        auto tinted = [](double t, double r) { return std::clamp(t * r, 0.05, 1.0); };
        grain["colour"]["end_grain"]["tint"] = colourJson(
            {tinted(tint.r, relative.r), tinted(tint.g, relative.g), tinted(tint.b, relative.b)});
        scaleWoodColours(grain, sideRatio);
        faces = rebake();
    }
    // One tint for every end face: where they differ among themselves (a stain on one), it
    // may fit them no better than the preset's; it is kept only if it does.
    if (bakes > 0 && !(colourMisfit(faces) < colourMisfit(bakedBefore))) {
        grain = before;
        faces = bakedBefore;
    }
    return bakes;
}

}  // namespace nenrin
