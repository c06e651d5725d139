#pragma once
/// The colour of the knots' wood: the grain's `colour.knots` darkening and tint, scaled so
/// that the bakes' knots have the photographs' mean colour there (hinoki's knot wood is a dark
/// red-brown the preset's knots do not reach).

#include <nlohmann/json.hpp>
#include <span>

#include "fit/wood_fit.h"

namespace nenrin {

/// Compares the mean colour of the fitted faces' photographs and bakes over the bakes' knot
/// wood (knot share 0.75 and more, at least 50 pixels) and moves `colour.knots.darkening`
/// and `tint` by their ratio. False when there is no knot wood to compare or nothing moved
/// (within 1 %).
bool matchKnotColour(nlohmann::json& grain, std::span<const FaceFigures> faces);

}  // namespace nenrin
