#pragma once
/// Observation tables for Akagi & Kitajima's hierarchical model: the hand-measured 13 parameters
/// of several trees of one species (paper section 4: "a tree-form database built by observing
/// several real trees per species and adjusting the parameters by hand").
///
/// Format (CSV, UTF-8): lines starting with '#' and blank lines are ignored; the first other line
/// is the header: a `tree` column (the individual's id, so that several rows - e.g. several
/// observed segments - of one tree share an individual effect) and the 13 parameter columns by
/// their paper names (Height, Radius, LeafNum, LeafSize, BranchNum, MainGrowth, MainAngle,
/// MainRotation, SubGrowth, SubAngle, BranchPoint, Horizontal, GrowthGain), in any order. Every
/// row needs a value in every column. Units as in akagi_params.h (m, degrees, shares). Errors
/// throw InputError naming the file and line.

#include <string>
#include <vector>

#include "skeleton/sources/akagi/akagi_params.h"

namespace nenrin {

struct ObservationTable {
    std::string source;                ///< file name (or "<species>" for built-in tables)
    std::vector<std::string> treeIds;  ///< distinct trees, in order of first appearance
    std::vector<AkagiParams> rows;     ///< one per observation
    std::vector<int> rowTree;          ///< index into treeIds per row
    std::vector<int> rowLine;          ///< 1-based line of each row in the source
};

/// Reads a table file.
ObservationTable loadAkagiObservations(const std::string& path);
/// Parses table text; `source` names it in error messages.
ObservationTable parseAkagiObservations(const std::string& text, const std::string& source);

}  // namespace nenrin
