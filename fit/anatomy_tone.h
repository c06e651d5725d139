#pragma once
/// The anatomy's tone taken out of the measured ring profile. The ring profile (step 7) is
/// read from photographs, so it already carries what the wood's anatomy does to each ring
/// phase on average: a ring-porous hardwood's band of large pores darkens its early wood,
/// thick late-wood cells darken the ring's end. The shader's anatomy then darkens the same
/// phases again, and the bakes' rings come out too contrasted (chestnut CN03: the profile
/// peaked at its darkest, E 1.0, in the band of pores; mid texture 1.49 x the photographs').
/// So the bakes with and without the anatomy are compared phase by phase, and the profile's
/// colour at each phase divided by the anatomy's darkening there (less its mean, which the
/// colour calibration keeps).

#include <nlohmann/json.hpp>
#include <span>
#include <vector>

#include "fit/wood_fit.h"

namespace nenrin {

/// The anatomy's darkening by ring phase over the fitted faces' stem wood (knot wood and held
/// out faces left out): at the late-wood profile's phases k / (n - 1), the luminance of the
/// bakes `withAnatomy` over that of the bakes `without` (the same faces, the grain's anatomy
/// off), divided by its mean over all phases; 1 where fewer than 50 pixels fall.
std::vector<double> anatomyTone(std::span<const FaceFigures> withAnatomy,
                                std::span<const FaceFigures> without, size_t n);

/// Divides the grain's ring colour at each phase of its `colour.late_wood_profile` by `tone`
/// (anatomyTone), E kept in [0, 1]. Nothing where the early and late wood's luminance are
/// within 1 % of each other or the grain has no profile. Returns whether it changed the grain.
bool removeAnatomyTone(nlohmann::json& grain, std::span<const double> tone);

}  // namespace nenrin
