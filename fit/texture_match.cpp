#include "fit/texture_match.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "grain/grain_params.h"

namespace nenrin {

namespace {

/// Bounds on the strengths as the shader applies them, so that the albedo filter stays
/// positive: the cells' noise amplitudes summed (each noise is within [-1, 1] and rarely near
/// it), each of the rest's amplitudes, the pores' darkening (its tint's largest channel is 1).
constexpr double kMaxCellSum = 0.8, kMaxRestAmplitude = 0.5, kMaxPoreDarkening = 1.0;
/// A ratio this close to 1 is matched; a strength moves at most this factor per bake, and
/// stays within these of the base grain's: the figures also carry texture the anatomy does not
/// make, which a weak lever would be pushed to its end to cancel.
constexpr double kMatched = 1.05, kMaxStep = 3, kMinStrength = 0.5, kMaxStrength = 2;
/// The slope (log ratio over log strength) is taken within these: texture of other origins
/// (ring edges, the rings' own contrast) makes it under 1.
constexpr double kMinSlope = 0.15, kMaxSlope = 1.5;

void setValue(nlohmann::json& grain, std::initializer_list<const char*> keys, double v) {
    nlohmann::json* j = &grain;
    for (const char* k : keys) j = &(*j)[k];
    *j = std::round(v * 1e4) / 1e4;
}

/// The base grain's strengths (as parsed, defaults included), and how the fitted ones set
/// them.
struct Anatomy {
    double fibre = 0, speckle = 0, streak = 0, tone = 0, pores = 0, endTexture, endContrast;

    explicit Anatomy(const GrainParams& g)
        : endTexture(g.colour.endGrainTexture), endContrast(g.colour.endGrainContrast) {
        const AnatomyParams& a = g.anatomy;
        if (!a.enabled) return;
        fibre = a.fibreAmplitude;
        speckle = a.speckleAmplitude;
        streak = a.streakAmplitude;
        tone = a.ringTone;
        pores = a.pores == PoreKind::None ? 0 : a.poreDarkening;
    }

    double cells() const { return fibre + speckle; }
    /// The largest factor the rest may take on end grain: each amplitude and the pores
    /// within bounds.
    double restCap() const {
        double cap = 5;
        for (double v : {streak, tone})
            if (v > 0) cap = std::min(cap, kMaxRestAmplitude / v);
        if (pores > 0) cap = std::min(cap, kMaxPoreDarkening / pores);
        return cap;
    }

    /// Writes `s` into the grain, clamped to what the bounds allow (the clamped values are
    /// put back in `s`). End grain shows the side's strengths times 1 + its term (the
    /// parser's -0.9 .. 4).
    void apply(nlohmann::json& g, TextureStrengths& s) const {
        s.sideCells = std::min(s.sideCells, kMaxCellSum / cells());
        setValue(g, {"anatomy", "fibres", "amplitude"}, fibre * s.sideCells);
        setValue(g, {"anatomy", "speckle", "amplitude"}, speckle * s.sideCells);
        const double texture = std::clamp((1 + endTexture) * s.endCells / s.sideCells, 0.1,
                                          std::min(5.0, kMaxCellSum / (cells() * s.sideCells))) -
                               1;
        const double contrast = std::clamp((1 + endContrast) * s.endRest, 0.1, restCap()) - 1;
        s.endCells = s.sideCells * (1 + texture) / (1 + endTexture);
        s.endRest = (1 + contrast) / (1 + endContrast);
        setValue(g, {"colour", "end_grain", "texture"}, texture);
        setValue(g, {"colour", "end_grain", "contrast"}, contrast);
    }
};

/// The geometric mean of one ratio over the fitted faces of one kind; 0 if there are none.
double meanRatio(const std::vector<FaceFigures>& faces, std::span<const double> endWeights,
                 bool end, bool fine) {
    double logSum = 0;
    int count = 0;
    for (size_t i = 0; i < faces.size(); ++i) {
        if (faces[i].heldOut || (endWeights[i] > 0.5) != end) continue;
        const double r = fine ? faces[i].fineRatio : faces[i].midRatio;
        if (!(r > 0)) continue;
        logSum += std::log(r);
        ++count;
    }
    return count > 0 ? std::exp(logSum / count) : 0;
}

/// One strength under fit: its last ratio, and the slope between its last two bakes.
struct Control {
    double* strength;
    bool end, fine;
    double ratio = 0, previousRatio = 0, previousStrength = 0, slope = 1;

    /// Takes the bakes' ratio; true if it wants a step (faces of its kind, not matched).
    bool measure(const std::vector<FaceFigures>& faces, std::span<const double> endWeights) {
        previousRatio = ratio;
        ratio = meanRatio(faces, endWeights, end, fine);
        if (previousRatio > 0 && ratio > 0 && previousStrength > 0 &&
            std::abs(std::log(*strength / previousStrength)) > 1e-3) {
            const double s =
                std::log(ratio / previousRatio) / std::log(*strength / previousStrength);
            slope = std::clamp(std::isfinite(s) ? s : kMaxSlope, kMinSlope, kMaxSlope);
        }
        previousStrength = *strength;
        return ratio > 0 && std::abs(std::log(ratio)) > std::log(kMatched);
    }
    void step() const {
        *strength =
            std::clamp(*strength * std::clamp(std::pow(ratio, -1 / slope), 1 / kMaxStep, kMaxStep),
                       kMinStrength, kMaxStrength);
    }
};

}  // namespace

TextureStrengths matchTexture(nlohmann::json& grain, std::vector<FaceFigures>& faces,
                              std::span<const double> endWeights,
                              const std::function<std::vector<FaceFigures>()>& rebake) {
    TextureStrengths s;
    const Anatomy base(parseGrain(grain, "the fitted grain"));
    if (base.cells() <= 0) return s;
    std::array<Control, 3> controls = {Control{&s.sideCells, false, true},
                                       Control{&s.endCells, true, true},
                                       Control{&s.endRest, true, false}};
    for (int round = 0; round < kTextureRounds; ++round) {
        const TextureStrengths before = s;
        for (Control& c : controls)
            if (c.measure(faces, endWeights)) c.step();
        // Without end faces, end grain follows the side; its rest is fitted through its
        // pores alone (without pores it stays the base grain's).
        if (controls[1].ratio == 0) s.endCells = s.sideCells;
        if (controls[2].ratio == 0 || base.pores == 0) s.endRest = 1;
        base.apply(grain, s);
        // Nothing moved (all matched, or held at their bounds): another bake would show the
        // same.
        const double moved = std::max({std::abs(std::log(s.sideCells / before.sideCells)),
                                       std::abs(std::log(s.endCells / before.endCells)),
                                       std::abs(std::log(s.endRest / before.endRest))});
        if (moved < 1e-3) break;
        faces = rebake();
        ++s.bakes;
    }
    return s;
}

}  // namespace nenrin
