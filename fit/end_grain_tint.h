#pragma once
/// The colour of end grain. Open cell ends trap light: an end face photographs darker and
/// redder than the side faces of the same wood, by an amount the species preset can only
/// guess (the hinoki cube's end faces are 3 and 14 L* darker than its lightest side faces).
/// With end and side faces both fitted, `colour.end_grain.tint` is set to the end faces' median
/// colour over the side faces', and the early and late wood colours to the side faces' mean.

#include <functional>
#include <nlohmann/json.hpp>
#include <span>
#include <utility>
#include <vector>

#include "fit/wood_fit.h"
#include "grain/rgb.h"

namespace nenrin {

/// Which fitted faces a colour ratio is taken over.
enum class FaceKind { Any, Side, End };

/// The photographed mean colour of the fitted faces of `kind` over their baked one, per
/// channel (linear); (1, 1, 1) where there are none. `endWeights`: each face's end-grain
/// weight (a face is end grain over 0.5), needed unless `kind` is Any.
Rgb colourRatio(std::span<const FaceFigures> faces, FaceKind kind = FaceKind::Any,
                std::span<const double> endWeights = {});

/// How well the fitted faces' mean colours match, worst first: how many differ by more than
/// the 5 dE*ab, then the root mean square of the differences.
std::pair<int, double> colourMisfit(std::span<const FaceFigures> faces);

/// The largest |log| of a ratio's channels: how far it is from (1, 1, 1).
double worstLog(const Rgb& ratio);

/// A colour as the fit writes it into a grain: each channel to four decimals.
nlohmann::json colourJson(const Rgb& c);

/// Scales the grain's early and late wood colours by `ratio`, each channel at most 1 (a
/// grain's colours are reflectances, however dark the bake).
void scaleWoodColours(nlohmann::json& grain, const Rgb& ratio);

/// Sets the end-grain tint (and scales the early and late wood) as above, `rounds` times or
/// until both kinds are within half a percent; `faces` are the bakes of `grain`, `rebake`
/// bakes them again from it. Kept only if the fitted faces' colours match better: fewer of
/// them over 5 dE*ab, or as many and a lower RMS difference (else `grain` and `faces` are as
/// they were). Without fitted faces of both kinds, changes
/// nothing. Returns the bakes it took.
int matchEndGrainTint(nlohmann::json& grain, std::vector<FaceFigures>& faces,
                      std::span<const double> endWeights,
                      const std::function<std::vector<FaceFigures>()>& rebake, int rounds);

}  // namespace nenrin
