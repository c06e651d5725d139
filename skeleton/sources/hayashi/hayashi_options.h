#pragma once
/// Parameters of the Hayashi & Takahashi conifer model (docs/tree-hayashi.md): presets for
/// sugi (Cryptomeria japonica), hinoki (Chamaecyparis obtusa) and a whorled pine (Pinus
/// densiflora, Fig. 12), validation, and overrides read from a JSON object.
///
/// Units: metres, years, radians (the JSON keys take degrees).

#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include "util/json_reader.h"

namespace nenrin {

/// How first-order branches leave the trunk.
enum class BranchArrangement {
    Spiral,  ///< one at a time on a spiral rising with height growth (sugi, hinoki)
    Whorled  ///< several at one height once a year (pine)
};

/// A side-branch order (2nd, 3rd, 4th = foliage): where its branches sit and how long they get.
struct SubBranchOrder {
    double spacing = 0.05;   ///< m between consecutive branches along the parent
    double maxLength = 0.2;  ///< m: the length at the parent's base (constant profile: everywhere)
    bool parabolic = false;  ///< length maxLength sqrt(1 - s / parent length): long at the base
    double speed = 0.2;      ///< m/year: how fast the branch elongates
};

struct HayashiOptions {
    static constexpr double kDegree = std::numbers::pi / 180;  ///< radians per degree

    std::string preset = "sugi";  ///< the preset these values started from (provenance only)
    uint64_t seed = 1;
    int years = 20;    ///< age of the tree at the end (years >= 1)
    int maxOrder = 4;  ///< 1 = trunk + first-order branches ... 4 = with foliage

    // Trunk: seasonal height growth.
    double heightGrowth = 0.5;  ///< m/year, mean leader growth
    double heightGrowthVariation =
        0.15;                    ///< coefficient of variation between years (good and bad years)
    double growingSeason = 0.5;  ///< fraction of the year the leader grows (spring..summer)
    double seasonShape = 2;      ///< p >= 1: the year's growth done by season fraction u is
                                 ///< 1 - (1 - u)^p (fast in spring, zero at the end)
    double ringWidth = 0.005;    ///< m/year of trunk radius (radii of the preview)

    // Crown (eq. 2) and self-pruning.
    double crownCoefficient = 0.3;       ///< a of y = a (1 - z)^0.5
    double branchLengthVariation = 0.1;  ///< relative sd of a branch's length about eq. 2
    double crownRatio = 0.55;            ///< live crown length / tree height; below it branches die

    // First-order branch arrangement.
    BranchArrangement arrangement = BranchArrangement::Spiral;
    double turnsPerYear = 3.19;          ///< spiral turns per year (Table 1 mean; 2.1..5.0)
    double branchesPerTurn = 2.10;       ///< first-order branches per turn (Table 1 mean; 1.9..2.5)
    double divergenceSd = 73 * kDegree;  ///< sd of the angle between consecutive branches
    double divergenceMin = 33 * kDegree;   ///< smallest angle between consecutive branches
    double divergenceMax = 293 * kDegree;  ///< largest angle between consecutive branches
    bool clockwise = true;                 ///< the spiral turns clockwise seen from above
    int whorlMin = 3, whorlMax = 5;        ///< branches per whorl (Whorled)
    double whorlJitter = 10 * kDegree;     ///< sd of a whorl branch's azimuth about even spacing

    // First-order branch geometry and growth.
    double elevation = 10 * kDegree;   ///< above horizontal (alpha = 80 deg to the trunk)
    double elevationSd = 5 * kDegree;  ///< sd of the elevation
    double gamma = 0.35;               ///< first-order radial speed / trunk radial speed (mean)
    double gammaVariation = 0.2;       ///< gamma drawn uniformly in gamma (1 -+ variation)
    double gammaOrderRatio = 0.6;  ///< each further order thickens this much slower than its parent

    // Second to fourth order (section 6.1).
    double elongationAngle = 80 * kDegree;  ///< alpha: every side branch to its parent
    SubBranchOrder second{0.05, 0.20, false, 0.2};
    SubBranchOrder third{0.02, 0.06, true, 0.1};
    SubBranchOrder fourth{0.003, 0.015, true, 0.05};

    /// Average first-order branches per year (turns per year x branches per turn).
    double branchesPerYear() const { return turnsPerYear * branchesPerTurn; }
    /// The mean divergence angle (rad) that gives branchesPerTurn: one turn / branches per turn.
    double divergenceMean() const;
};

/// "sugi", "hinoki", "pine".
std::vector<std::string> hayashiPresetNames();
/// The preset's options; InputError (naming the valid presets) for an unknown name.
HayashiOptions hayashiPreset(const std::string& name);
/// Throws InputError (location "hayashi options", the JSON key of the bad field) unless every
/// field is finite and in range.
void validateHayashiOptions(const HayashiOptions& options);

/// Overrides from a JSON object (keys in docs/tree-hayashi.md, angles in degrees): starts from
/// `base`, or from the preset named by a "preset" key; unknown keys are errors (finish() is
/// called). The result is validated.
HayashiOptions readHayashiOptions(JsonReader& reader, const HayashiOptions& base);
/// Every option under its JSON key (angles in degrees, no "preset" key), for the skeleton
/// file's provenance: readHayashiOptions of it gives the same options back.
nlohmann::json hayashiOptionsToJson(const HayashiOptions& options);
/// The same for a JSON file (`--params file.json`).
HayashiOptions loadHayashiOptions(const std::string& path, const HayashiOptions& base);

}  // namespace nenrin
