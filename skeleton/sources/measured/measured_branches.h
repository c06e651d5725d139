#pragma once
/// Hayashi & Takahashi's measured-branch data (section 4.1, Figs. 14-16) as a skeleton source:
/// a trunk and hierarchically numbered branches (B100, B200 first order; B110, B120 on B100;
/// B111 on B110 ...), each a list of internodes D(l, theta, phi, d) = length, azimuth,
/// elevation, base diameter, summed from the ground up with
///
///     x = l sin(theta) cos(phi),  y = l cos(theta) cos(phi),  z = l sin(phi).
///
/// The JSON format ("nenrin-measured-branches") is documented in docs/tree-hayashi.md; every
/// problem is an InputError naming the file and the JSON path (`branches.B120.node`).

#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "skeleton/skeleton.h"

namespace nenrin {

struct MeasuredTree {
    Skeleton skeleton;
    std::map<std::string, uint32_t> chainOfBranch;  ///< "B120" -> chain id (the trunk is 0)
    double age = 0;              ///< years at measurement (newest tip, or the file's "age")
    double elongationSpeed = 0;  ///< m/year: Sa used for the birth times
};

/// Builds the tree from parsed JSON; `file` names the source in error messages.
MeasuredTree parseMeasuredTree(const nlohmann::json& json, const std::string& file);
MeasuredTree loadMeasuredTree(const std::string& path);
/// The skeleton alone (what `nenrin tree` needs).
Skeleton loadMeasuredBranches(const std::string& path);

}  // namespace nenrin
