#include "fit/fitted_grain.h"

#include <cmath>

#include "fit/end_grain_tint.h"
#include "grain/grain_params.h"
#include "util/input_error.h"
#include "util/json_parse.h"

namespace nenrin {

namespace {

double rounded(double v, double unit) { return std::round(v / unit) * unit; }

}  // namespace

nlohmann::json fittedGrain(const std::string& base, const Sample& sample,
                           const RadialRings& profile) {
    nlohmann::json grain = base.empty() ? nlohmann::json::object() : parseJsonFile(base);
    if (!grain.is_object()) throw InputError(base, "", "expected a grain file (a JSON object)");
    parseGrain(grain, base);  // a valid grain file, or the error names it
    // The ring geometry is the fit's: the skeleton's line and ring series and the warp. The
    // base's own ring shapes (sway, wander, eccentric growth, ageing, taper, a ring-width
    // model) would move the rings off the photographed ones.
    for (const char* key : {"sway", "wander", "direction", "age", "taper", "rings", "warp"})
        grain.erase(key);
    const ColourStrip& s = profile.strip;
    const std::vector<double>& b = profile.boundaries;
    grain["radial_speed"] = rounded((b.back() - b.front()) / double(b.size() - 1), 1e-6);
    nlohmann::json& colour = grain["colour"];
    if (!colour.is_object()) colour = nlohmann::json::object();
    colour["early_wood"] = colourJson(s.earlyWood);
    colour["late_wood"] = colourJson(s.lateWood);
    nlohmann::json shape = nlohmann::json::array();
    for (double e : s.lateWoodProfile) shape.push_back(rounded(e, 1e-3));
    colour["late_wood_profile"] = shape;
    // A sample a few centimetres across is heartwood or sapwood, rarely both: its colour is
    // the early and late wood above.
    colour["heartwood"] = {{"enabled", false}};
    // The base's halo round the knots (the hinoki preset's) is the fit's to find (step 10):
    // until then it would widen the bakes' dark knot wood, which sizes and aims the branches.
    // Its knots' ring wobble: the finder reads wobbling faint knot rings off (the synthetic
    // knot cube's F knot 18 mm at 0.5 years), so the fit bakes circles (given back at its end).
    if (colour.contains("knots") && colour["knots"].is_object()) {
        colour["knots"]["halo_tint"] = colourJson({1, 1, 1});
        colour["knots"].erase("ring_wobble");
    }
    grain["reference"] = {{"fit", sample.file},
                          {"base", base},
                          {"rings", s.rings},
                          {"ring_width_cv", s.widthStatistics.cv},
                          {"early_wood_lab", {s.early.L, s.early.a, s.early.b}},
                          {"late_wood_lab", {s.late.L, s.late.a, s.late.b}}};
    return grain;
}

nlohmann::json withBaseLook(nlohmann::json grain, const std::string& base) {
    if (base.empty()) return grain;
    const GrainParams look = parseGrain(parseJsonFile(base), base);
    if (look.colour.knotRingWobble > 0)
        grain["colour"]["knots"]["ring_wobble"] = look.colour.knotRingWobble;
    return grain;
}

}  // namespace nenrin
