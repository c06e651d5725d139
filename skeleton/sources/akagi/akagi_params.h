#pragma once
/// Akagi & Kitajima's 13 tree parameters (docs/design/models.md §5, paper section 2.3): the whole
/// description of a tree's form in their generator. Lengths in metres, angles in degrees (the unit
/// of the observation tables), shares and ratios unitless. The index order P1..P13 is the paper's
/// and is used by the statistical model (akagi_model.h) and the observation tables.

#include <array>
#include <nlohmann/json.hpp>
#include <string>

namespace nenrin {

class JsonReader;

inline constexpr int kAkagiParamCount = 13;

struct AkagiParams {
    double height = 10;         ///< P1 Height: tree height after scaling (m)
    double radius = 0.2;        ///< P2 Radius: trunk radius at the base (m)
    double leafNum = 4;         ///< P3 LeafNum: leaves at each leaf-bearing tip (count)
    double leafSize = 0.08;     ///< P4 LeafSize: leaf length (m)
    double branchNum = 3;       ///< P5 BranchNum: children per branch point, main + laterals
    double mainGrowth = 0.6;    ///< P6 MainGrowth: share of the growth element to the main axis
    double mainAngle = 5;       ///< P7 MainAngle: main axis tilt from its parent (deg)
    double mainRotation = 137;  ///< P8 MainRotation: turn of the branching plane per step (deg)
    double subGrowth = 0.2;     ///< P9 SubGrowth: share of the growth element to each lateral
    double subAngle = 45;       ///< P10 SubAngle: lateral tilt from its parent (deg)
    double branchPoint = 0.3;   ///< P11 BranchPoint: first fork along an axis / axis length
    double horizontal = 0.2;    ///< P12 Horizontal: pull of laterals toward the horizontal [0,1]
    double growthGain = 0.5;    ///< P13 GrowthGain: shade suppression of lower laterals (>= 0)

    /// P(i+1): 0 = Height ... 12 = GrowthGain.
    double& operator[](int i);
    double operator[](int i) const;
};

/// The paper's names, in P1..P13 order ("Height", ..., "GrowthGain"); also the CSV column names
/// and JSON keys.
const std::array<const char*, kAkagiParamCount>& akagiParamNames();
/// Index 0..12 of a parameter name, or -1.
int akagiParamIndex(const std::string& name);
/// Empty if the value is allowed for parameter i, else what was expected ("a number in (0, 1)").
std::string akagiParamProblem(int i, double value);
/// Throws InputError naming `source` and the parameter if any value is NaN or out of range.
void validateAkagiParams(const AkagiParams& p, const std::string& source);

nlohmann::json akagiParamsToJson(const AkagiParams& p);
/// Reads an object with any of the 13 keys (others keep their defaults); unknown keys and bad
/// values throw InputError.
AkagiParams akagiParamsFromJson(JsonReader& reader);

}  // namespace nenrin
