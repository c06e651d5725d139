#pragma once
/// The grain file a fit starts from: the base grain (a species preset) for the anatomy and the
/// knots' look, with the fit's ring width and colours, and none of the base's own ring shapes.

#include <nlohmann/json.hpp>
#include <string>

#include "fit/radial_rings.h"
#include "fit/sample_file.h"

namespace nenrin {

/// `base`: a grain file ("" for the defaults). The base's ring shapes (sway, wander, eccentric
/// growth, ageing, taper, a ring-width model, a warp) are taken out, its heartwood off, its
/// knots' halo off (step 10 of docs/fit.md finds one) and their rings' wobble off (given back
/// by withBaseLook); the early and late wood, their profile and the radial speed are the
/// measured rings'.
nlohmann::json fittedGrain(const std::string& base, const Sample& sample,
                           const RadialRings& profile);

/// The fitted grain with the base's look that the fit's bakes go without: its knots' ring
/// wobble (colour.knots.ring_wobble), if it has one.
nlohmann::json withBaseLook(nlohmann::json grain, const std::string& base);

}  // namespace nenrin
