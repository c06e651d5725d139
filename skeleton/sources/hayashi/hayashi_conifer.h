#pragma once
/// Hayashi & Takahashi's conifer tree model ("On the modeling of tree's figure": sugi, hinoki;
/// docs/tree-hayashi.md) as a skeleton source.
///
/// A straight trunk grows in height each spring and stops in autumn; first-order branches
/// leave it on a spiral that turns a few times a year (sugi, hinoki) or in yearly whorls
/// (pine), and lengthen with the tree so that their lengths follow the parabolic crown
/// y = a (1 - z)^0.5. Second to fourth order branches sit at fixed spacings along their parent,
/// at the elongation angle alpha to it and turned by a random beta about it. Branches below
/// the rising crown base die (dead knots). Every node carries the time its growth tip got there.

#include <array>
#include <cstdint>
#include <vector>

#include "skeleton/skeleton.h"
#include "skeleton/sources/hayashi/hayashi_options.h"

namespace nenrin {

/// One first-order branch as the paper measured them (Fig. 1: height, azimuth, length).
struct HayashiBranchRecord {
    int32_t chain = kNone;  ///< chain id in the skeleton; kNone if too short to be added (< 0.5 mm)
    double height = 0;      ///< m: where it leaves the trunk
    double azimuth = 0;     ///< rad in [0, 2 pi), from +X towards +Y (counter-clockwise from above)
    double spiralAngle =
        0;                 ///< rad: rotation along the spiral since the first branch (0 in whorls)
    double elevation = 0;  ///< rad above horizontal
    double birthTime = 0;  ///< years: when it left the trunk
    double length = 0;     ///< m at the end of growth (at death for a dead branch)
    double deathTime = kNeverDies;  ///< years; kNeverDies while inside the live crown
    double gamma = 0;               ///< radial speed relative to the trunk
    int year = 0;                   ///< growth year it was born in: floor(birthTime)
    int whorl = -1;                 ///< whorl index (whorled trees), -1 on a spiral
};

struct HayashiTree {
    Skeleton skeleton;
    std::vector<HayashiBranchRecord> firstOrder;  ///< in order of birth
    /// Entry y is the trunk height at the start of year y (entry 0 = 0, last = final height).
    std::vector<double> yearStartHeights;
    std::vector<int> branchesPerYear;  ///< first-order branches born in each year
    double height = 0;                 ///< m at the end
    double crownBase = 0;              ///< m: (1 - crownRatio) height; branches below are dead
    std::array<size_t, 5> chainsPerOrder{};    ///< index = order (0 = trunk)
    std::array<size_t, 5> segmentsPerOrder{};  ///< index = order
};

/// Grows the tree for options.years years. Validates the options first (InputError).
HayashiTree growHayashiConifer(const HayashiOptions& options);

}  // namespace nenrin
