#pragma once
/// How strongly the texture shows. The base grain (a species preset) brings the anatomy —
/// cells, rays, pores, streaks — but how strongly it shows in a photograph depends on the
/// timber, the surface, the light and the camera: the presets left the hinoki cube's end face
/// B with 0.62 of the photo's fine texture and the chestnut's end face D with 0.55 of its fine
/// and 0.44 of its mid texture. Three strengths are fitted, each to the geometric mean of one
/// figure over one kind of face (photo-stats' fine and mid energy ratios):
///   side faces, fine   the cells: anatomy.fibres.amplitude and anatomy.speckle.amplitude
///   end faces, fine    colour.end_grain.texture (the cells' contrast across the fibre)
///   end faces, mid     colour.end_grain.contrast (streaks, ring tone and pores across the
///                      fibre), only where the anatomy has pores: the open vessels of end
///                      grain; streaks cut across are blotches (the hinoki's end faces went
///                      grey and mottled when they were strengthened)
/// Side faces' mid texture is left to the rings: the anatomy's streaks and ring tone are a weak
/// lever on it, which the fit pushed to its bound to cancel contrast of other origins (a
/// knot's rings in the synthetic round trip). A face is end grain where the shader's end-grain
/// weight (|cos(normal, pith)|^4) is over one half, side grain where it is under. Each
/// strength moves by the power of its ratio that the last two bakes' slope (log ratio over log
/// strength) gives, starting from slope 1.

#include <functional>
#include <nlohmann/json.hpp>
#include <span>
#include <vector>

#include "fit/wood_fit.h"

namespace nenrin {

/// Fits the strengths of `grain`'s anatomy to the photographs (TextureStrengths, wood_fit.h).
/// Without end faces among the fitted ones, end grain follows the side's strengths. `faces` are the
/// bakes of `grain` as it is, `endWeights` each face's end-grain weight (same order); `rebake`
/// bakes the faces again from `grain`. Stops when every ratio is within 5 % of 1, a strength
/// reaches its bound, or after kTextureRounds bakes; leaves `faces` the bakes of the final `grain`.
/// A grain without anatomy is left as it is.
TextureStrengths matchTexture(nlohmann::json& grain, std::vector<FaceFigures>& faces,
                              std::span<const double> endWeights,
                              const std::function<std::vector<FaceFigures>()>& rebake);

constexpr int kTextureRounds = 4;

}  // namespace nenrin
