#include "skeleton/sources/hayashi/hayashi_options.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "util/input_error.h"

namespace nenrin {

namespace {

constexpr double kDeg = HayashiOptions::kDegree;
constexpr const char* kOptionsName = "hayashi options";

HayashiOptions sugi() { return HayashiOptions{}; }

HayashiOptions hinoki() {
    HayashiOptions o;
    o.preset = "hinoki";
    o.heightGrowth = 0.35;  // 11-year trees 3-4 m tall (section 2.1)
    o.crownCoefficient = 0.28;
    o.crownRatio = 0.6;
    // Divergence: mean 164 deg (Fig. 3) = 360 / 2.195 branches per turn. Turns per year were
    // not measured for hinoki (no tree was measured to the top); sugi-like 3.0 is assumed.
    o.turnsPerYear = 3.0;
    o.branchesPerTurn = 360.0 / 164.0;
    o.divergenceSd = 52 * kDeg;
    o.divergenceMin = 52 * kDeg;
    o.divergenceMax = 244 * kDeg;
    o.elevation = 15 * kDeg;
    o.gamma = 0.3;
    o.fourth = {0.003, 0.01, true, 0.05};  // scale-leaf sprays: shorter foliage
    return o;
}

HayashiOptions pine() {
    HayashiOptions o;
    o.preset = "pine";
    o.arrangement = BranchArrangement::Whorled;
    o.heightGrowth = 0.6;
    o.crownCoefficient = 0.35;
    o.crownRatio = 0.4;  // shade-intolerant: a short live crown
    o.whorlMin = 3;
    o.whorlMax = 5;
    o.elevation = 20 * kDeg;
    o.gamma = 0.4;
    // Illustrative, not from the paper: sparser, longer shoots and 8 cm needles.
    o.second = {0.15, 0.30, false, 0.3};
    o.third = {0.05, 0.10, true, 0.15};
    o.fourth = {0.01, 0.08, true, 0.1};
    return o;
}

[[noreturn]] void reject(const std::string& key, const std::string& expected, double value) {
    throw InputError(kOptionsName, key, fmt::format("expected {}, found {}", expected, value));
}

void requirePositive(const std::string& key, double v) {
    if (!(std::isfinite(v) && v > 0)) reject(key, "a finite number > 0", v);
}

void requireRange(const std::string& key, double v, double lo, double hi,
                  const std::string& unit = "") {
    if (!(std::isfinite(v) && v >= lo && v <= hi))
        reject(key, fmt::format("a number in [{}, {}]{}", lo, hi, unit), v);
}

void validateOrder(const std::string& key, const SubBranchOrder& s) {
    // Spacing below 0.1 mm would make millions of branches per metre.
    requireRange(key + ".spacing", s.spacing, 1e-4, 100, " m");
    requirePositive(key + ".length", s.maxLength);
    requirePositive(key + ".speed", s.speed);
}

void readOrder(JsonReader& parent, const std::string& key, SubBranchOrder& s) {
    auto r = parent.object(key);
    if (!r) return;
    s.spacing = r->number("spacing", s.spacing);
    s.maxLength = r->number("length", s.maxLength);
    s.speed = r->number("speed", s.speed);
    if (r->has("profile"))
        s.parabolic = r->choice("profile", "", {"constant", "parabolic"}) == "parabolic";
    r->finish();
}

}  // namespace

double HayashiOptions::divergenceMean() const { return 2 * std::numbers::pi / branchesPerTurn; }

std::vector<std::string> hayashiPresetNames() { return {"sugi", "hinoki", "pine"}; }

HayashiOptions hayashiPreset(const std::string& name) {
    if (name == "sugi") return sugi();
    if (name == "hinoki") return hinoki();
    if (name == "pine") return pine();
    std::string list;
    for (const auto& n : hayashiPresetNames()) list += (list.empty() ? "" : ", ") + n;
    throw InputError(kOptionsName, "preset",
                     fmt::format("unknown preset \"{}\": expected one of {}", name, list));
}

void validateHayashiOptions(const HayashiOptions& o) {
    if (o.years < 1 || o.years > 500) reject("years", "an integer in [1, 500]", o.years);
    if (o.maxOrder < 1 || o.maxOrder > 4) reject("max_order", "an integer in [1, 4]", o.maxOrder);
    requirePositive("height_growth", o.heightGrowth);
    requireRange("height_growth_variation", o.heightGrowthVariation, 0, 0.9);
    if (!(std::isfinite(o.growingSeason) && o.growingSeason > 0 && o.growingSeason <= 1))
        reject("growing_season", "a fraction of the year in (0, 1]", o.growingSeason);
    requireRange("season_shape", o.seasonShape, 1, 20);
    requirePositive("ring_width", o.ringWidth);
    requirePositive("crown_coefficient", o.crownCoefficient);
    requireRange("branch_length_variation", o.branchLengthVariation, 0, 0.9);
    if (!(std::isfinite(o.crownRatio) && o.crownRatio > 0 && o.crownRatio <= 1))
        reject("crown_ratio", "a number in (0, 1]", o.crownRatio);
    requireRange("turns_per_year", o.turnsPerYear, 0.1, 20);
    requireRange("divergence_min", o.divergenceMin / kDeg, 0, 360, " degrees");
    requireRange("divergence_max", o.divergenceMax / kDeg, 0, 360, " degrees");
    if (!(o.divergenceMax - o.divergenceMin >= 1 * kDeg))
        reject("divergence_max", "at least 1 degree more than divergence_min",
               o.divergenceMax / kDeg);
    requireRange("divergence_sd", o.divergenceSd / kDeg, 0.5, 360, " degrees");
    // The mean divergence (one turn / branches per turn) must lie inside [min, max].
    double meanDeg = 360 / o.branchesPerTurn;
    if (!(std::isfinite(o.branchesPerTurn) && o.branchesPerTurn > 0 &&
          meanDeg > o.divergenceMin / kDeg + 0.5 && meanDeg < o.divergenceMax / kDeg - 0.5))
        reject("branches_per_turn",
               fmt::format("a number > 0 whose divergence 360 / branches_per_turn lies inside "
                           "divergence_min..divergence_max ({:g}..{:g} degrees)",
                           o.divergenceMin / kDeg, o.divergenceMax / kDeg),
               o.branchesPerTurn);
    if (o.whorlMin < 1 || o.whorlMin > 20) reject("whorl_min", "an integer in [1, 20]", o.whorlMin);
    if (o.whorlMax < o.whorlMin || o.whorlMax > 20)
        reject("whorl_max", "an integer in [whorl_min, 20]", o.whorlMax);
    requireRange("whorl_jitter", o.whorlJitter / kDeg, 0, 90, " degrees");
    requireRange("elevation", o.elevation / kDeg, -90, 90, " degrees");
    requireRange("elevation_sd", o.elevationSd / kDeg, 0, 45, " degrees");
    requirePositive("gamma", o.gamma);
    requireRange("gamma_variation", o.gammaVariation, 0, 0.95);
    requirePositive("gamma_order_ratio", o.gammaOrderRatio);
    requireRange("elongation_angle", o.elongationAngle / kDeg, 1, 179, " degrees");
    validateOrder("second_order", o.second);
    validateOrder("third_order", o.third);
    validateOrder("fourth_order", o.fourth);
}

HayashiOptions readHayashiOptions(JsonReader& r, const HayashiOptions& base) {
    HayashiOptions o = base;
    if (r.has("preset")) {
        std::string name = r.string("preset", "");
        try {
            o = hayashiPreset(name);
        } catch (const InputError& e) {
            throw r.error("preset", e.message());
        }
    }
    if (r.has("seed"))  // JSON integers stop at 2^63 - 1; a larger base seed is kept as is
        o.seed = static_cast<uint64_t>(r.integer("seed", 0, 0, 0x7fffffffffffffffll));
    o.years = static_cast<int>(r.integer("years", o.years, 1, 500));
    o.maxOrder = static_cast<int>(r.integer("max_order", o.maxOrder, 1, 4));
    o.heightGrowth = r.number("height_growth", o.heightGrowth);
    o.heightGrowthVariation = r.number("height_growth_variation", o.heightGrowthVariation);
    o.growingSeason = r.number("growing_season", o.growingSeason);
    o.seasonShape = r.number("season_shape", o.seasonShape);
    o.ringWidth = r.number("ring_width", o.ringWidth);
    o.crownCoefficient = r.number("crown_coefficient", o.crownCoefficient);
    o.branchLengthVariation = r.number("branch_length_variation", o.branchLengthVariation);
    o.crownRatio = r.number("crown_ratio", o.crownRatio);
    if (r.has("arrangement"))
        o.arrangement = r.choice("arrangement", "", {"spiral", "whorled"}) == "whorled"
                            ? BranchArrangement::Whorled
                            : BranchArrangement::Spiral;
    o.turnsPerYear = r.number("turns_per_year", o.turnsPerYear);
    o.branchesPerTurn = r.number("branches_per_turn", o.branchesPerTurn);
    o.divergenceSd = r.number("divergence_sd", o.divergenceSd / kDeg) * kDeg;
    o.divergenceMin = r.number("divergence_min", o.divergenceMin / kDeg) * kDeg;
    o.divergenceMax = r.number("divergence_max", o.divergenceMax / kDeg) * kDeg;
    o.clockwise = r.boolean("clockwise", o.clockwise);
    o.whorlMin = static_cast<int>(r.integer("whorl_min", o.whorlMin, 1, 20));
    o.whorlMax = static_cast<int>(r.integer("whorl_max", o.whorlMax, 1, 20));
    o.whorlJitter = r.number("whorl_jitter", o.whorlJitter / kDeg) * kDeg;
    o.elevation = r.number("elevation", o.elevation / kDeg) * kDeg;
    o.elevationSd = r.number("elevation_sd", o.elevationSd / kDeg) * kDeg;
    o.gamma = r.number("gamma", o.gamma);
    o.gammaVariation = r.number("gamma_variation", o.gammaVariation);
    o.gammaOrderRatio = r.number("gamma_order_ratio", o.gammaOrderRatio);
    o.elongationAngle = r.number("elongation_angle", o.elongationAngle / kDeg) * kDeg;
    readOrder(r, "second_order", o.second);
    readOrder(r, "third_order", o.third);
    readOrder(r, "fourth_order", o.fourth);
    r.finish();
    try {
        validateHayashiOptions(o);
    } catch (const InputError& e) {
        // Same key, but located in this file.
        throw InputError(r.file(), r.pathOf(e.where()), e.message());
    }
    return o;
}

nlohmann::json hayashiOptionsToJson(const HayashiOptions& o) {
    auto order = [](const SubBranchOrder& s) {
        return nlohmann::json{{"spacing", s.spacing},
                              {"length", s.maxLength},
                              {"profile", s.parabolic ? "parabolic" : "constant"},
                              {"speed", s.speed}};
    };
    return nlohmann::json{
        {"seed", o.seed},
        {"years", o.years},
        {"max_order", o.maxOrder},
        {"height_growth", o.heightGrowth},
        {"height_growth_variation", o.heightGrowthVariation},
        {"growing_season", o.growingSeason},
        {"season_shape", o.seasonShape},
        {"ring_width", o.ringWidth},
        {"crown_coefficient", o.crownCoefficient},
        {"branch_length_variation", o.branchLengthVariation},
        {"crown_ratio", o.crownRatio},
        {"arrangement", o.arrangement == BranchArrangement::Whorled ? "whorled" : "spiral"},
        {"turns_per_year", o.turnsPerYear},
        {"branches_per_turn", o.branchesPerTurn},
        {"divergence_sd", o.divergenceSd / kDeg},
        {"divergence_min", o.divergenceMin / kDeg},
        {"divergence_max", o.divergenceMax / kDeg},
        {"clockwise", o.clockwise},
        {"whorl_min", o.whorlMin},
        {"whorl_max", o.whorlMax},
        {"whorl_jitter", o.whorlJitter / kDeg},
        {"elevation", o.elevation / kDeg},
        {"elevation_sd", o.elevationSd / kDeg},
        {"gamma", o.gamma},
        {"gamma_variation", o.gammaVariation},
        {"gamma_order_ratio", o.gammaOrderRatio},
        {"elongation_angle", o.elongationAngle / kDeg},
        {"second_order", order(o.second)},
        {"third_order", order(o.third)},
        {"fourth_order", order(o.fourth)}};
}

HayashiOptions loadHayashiOptions(const std::string& path, const HayashiOptions& base) {
    nlohmann::json json = parseJsonFile(path);
    JsonReader reader(json, path);
    return readHayashiOptions(reader, base);
}

}  // namespace nenrin
