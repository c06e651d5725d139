#include "skeleton/sources/akagi/akagi_params.h"

#include <cmath>
#include <sstream>

#include "util/input_error.h"
#include "util/json_reader.h"

namespace nenrin {

namespace {

/// Unit and allowed range of a parameter, for messages.
struct AkagiParamRange {
    double lo, hi;
    bool loInclusive;
    const char* unit;
};

// Shares must stay below 1 or an axis never runs out of growth element; counts need one child.
const std::array<AkagiParamRange, kAkagiParamCount> kRanges = {{
    {0, 200, false, "m"},         // Height
    {0, 5, false, "m"},           // Radius
    {0, 1000, true, "leaves"},    // LeafNum
    {0, 2, false, "m"},           // LeafSize
    {1, 12, true, "children"},    // BranchNum
    {0, 1, true, "share"},        // MainGrowth: 0 = dichotomous fork
    {-90, 90, true, "deg"},       // MainAngle
    {-360, 360, true, "deg"},     // MainRotation
    {0, 1, false, "share"},       // SubGrowth
    {-150, 150, true, "deg"},     // SubAngle
    {0, 0.95, true, "fraction"},  // BranchPoint
    {0, 1, true, "fraction"},     // Horizontal
    {0, 20, true, "gain"},        // GrowthGain
}};

std::string formatNumber(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

}  // namespace

double& AkagiParams::operator[](int i) {
    double* fields[kAkagiParamCount] = {
        &height,       &radius,    &leafNum,  &leafSize,    &branchNum,  &mainGrowth, &mainAngle,
        &mainRotation, &subGrowth, &subAngle, &branchPoint, &horizontal, &growthGain};
    return *fields[i];
}

double AkagiParams::operator[](int i) const { return const_cast<AkagiParams&>(*this)[i]; }

const std::array<const char*, kAkagiParamCount>& akagiParamNames() {
    static const std::array<const char*, kAkagiParamCount> names = {
        "Height",      "Radius",     "LeafNum",      "LeafSize",  "BranchNum",
        "MainGrowth",  "MainAngle",  "MainRotation", "SubGrowth", "SubAngle",
        "BranchPoint", "Horizontal", "GrowthGain"};
    return names;
}

int akagiParamIndex(const std::string& name) {
    const auto& names = akagiParamNames();
    for (int i = 0; i < kAkagiParamCount; ++i)
        if (name == names[i]) return i;
    return -1;
}

std::string akagiParamProblem(int i, double value) {
    const AkagiParamRange& r = kRanges[i];
    bool ok =
        std::isfinite(value) && (r.loInclusive ? value >= r.lo : value > r.lo) && value <= r.hi;
    // Shares of exactly 1 would make the growth element never fall below 1 along an axis.
    if (ok && (i == 5 || i == 8) && value >= 1) ok = false;
    if (ok) return {};
    std::string upper = (i == 5 || i == 8) ? ")" : "]";
    return std::string("expected a number in ") + (r.loInclusive ? "[" : "(") + formatNumber(r.lo) +
           ", " + formatNumber(r.hi) + upper + " (" + r.unit + "), found " + formatNumber(value);
}

void validateAkagiParams(const AkagiParams& p, const std::string& source) {
    for (int i = 0; i < kAkagiParamCount; ++i) {
        std::string problem = akagiParamProblem(i, p[i]);
        if (!problem.empty()) throw InputError(source, akagiParamNames()[i], problem);
    }
}

nlohmann::json akagiParamsToJson(const AkagiParams& p) {
    nlohmann::json j = nlohmann::json::object();
    for (int i = 0; i < kAkagiParamCount; ++i) j[akagiParamNames()[i]] = p[i];
    return j;
}

AkagiParams akagiParamsFromJson(JsonReader& reader) {
    AkagiParams p;
    for (int i = 0; i < kAkagiParamCount; ++i) {
        const char* name = akagiParamNames()[i];
        double v = reader.number(name, p[i]);
        std::string problem = akagiParamProblem(i, v);
        if (!problem.empty()) throw reader.error(name, problem);
        p[i] = v;
    }
    reader.finish();
    return p;
}

}  // namespace nenrin
