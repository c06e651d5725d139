#pragma once
/// The discoloured stem wood round the knots (`colour.knots.halo_*`, grain/knot_look.h): on the
/// hinoki cube H11 an orange, resin-soaked zone runs from its knot along the stem down to the
/// end face D, a fifth of that face (10.7 dE*ab between D's photograph and its bake without
/// it). Its reach is chosen among a few widths and stretches along the stem, its tint fitted
/// pixel by pixel where the bakes put it.

#include <functional>
#include <nlohmann/json.hpp>
#include <vector>

#include "fit/wood_fit.h"

namespace nenrin {

/// For each candidate reach: one bake with a grey probe tint gives each pixel's halo weight w
/// (its colour over the bake without a halo is 1 - w / 2), and the tint t per channel is the
/// least-squares fit of photo = bake x (1 + w (t - 1)) over the fitted faces' pixels. The
/// candidate with the smallest residual is baked with its tint and kept if the fitted faces'
/// colours then match better (fewer over 5 dE*ab, or as many and a lower RMS difference).
/// `grain` has no halo of its own (fittedGrain leaves the base grain's out); `faces` are its
/// bakes, `rebake` bakes them again from it; both are left as they were when no halo is kept.
/// Does nothing without knots in the bakes' reach.
HaloFit matchKnotHalo(nlohmann::json& grain, std::vector<FaceFigures>& faces,
                      const std::function<std::vector<FaceFigures>()>& rebake);

}  // namespace nenrin
