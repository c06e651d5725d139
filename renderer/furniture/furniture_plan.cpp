#include "renderer/furniture/furniture_plan.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "skeleton/skeleton_file.h"
#include "util/input_error.h"
#include "util/json_parse.h"
#include "util/json_reader.h"

namespace nenrin {

namespace {

/// A board is cut this much larger than its part on every side (the planer's allowance), so
/// the part lies inside the board.
constexpr double kAllowance = 0.002;
/// A part wider than the log gives is cut from a board narrowed by halves this often.
constexpr int kNarrowings = 4;

const char* sawingName(Sawing s) {
    return s == Sawing::Flat ? "flat" : s == Sawing::Quarter ? "quarter" : "mixed";
}

Sawing parseSawing(const JsonReader& r, const std::string& key, const std::string& text) {
    if (text == "flat") return Sawing::Flat;
    if (text == "quarter") return Sawing::Quarter;
    if (text == "mixed") return Sawing::Mixed;
    throw r.error(key, fmt::format("expected flat, quarter or mixed, found \"{}\"", text));
}

/// Cuts the part's board, narrowing it when the log is too small for its width.
void cutPartBoard(PartPlan& p, const GrowthField& field, const CutPlanParams& base) {
    CutPlanParams params = base;
    params.sawing = p.requested;
    const Vec3 size = p.frame.extent + Vec3{1, 1, 1} * (2 * kAllowance);
    double width = size.y;
    for (int attempt = 0; attempt <= kNarrowings; ++attempt, width *= 0.5) {
        p.board = cutBoard(field, params, size.x, width, size.z, p.seed);
        if (p.board) break;
    }
    if (!p.board) return;
    p.boardWidth = width;
    if (width < size.y)
        p.notes.push_back(fmt::format(
            "{:.3g} m wide: wider than a board this log gives, cut from a {:.3g} m board (the "
            "wood beyond it continues that board's log: the log is too small for this width)",
            size.y, width));
    p.sawing = sawingAsCut(p.board->treeFromLamella);
    p.treeFromModel = p.board->treeFromLamella * p.frame.modelFromPart().inverse();
}

}  // namespace

const GrownTree& TreeCache::tree(const std::string& skeleton, const std::string& grain) {
    auto& slot = trees_[{skeleton, grain}];
    if (!slot)
        slot = std::make_unique<GrownTree>(loadSkeletonFile(skeleton),
                                           grain.empty() ? GrainParams{} : loadGrainFile(grain));
    return *slot;
}

std::string sawingAsCut(const RigidTransform& treeFromLamella) {
    const Vec3& c = treeFromLamella.origin;
    const double r = std::hypot(c.x, c.y);
    if (r < 1e-9) return "quarter";  // through the pith: every ring meets the face at 90°
    const Vec3 radial{c.x / r, c.y / r, 0};
    // The rings run tangentially: their angle to the face is the face normal's to the radius.
    const double angle =
        std::acos(std::min(1.0, std::abs(dot(treeFromLamella.z, radial)))) * 180 / std::numbers::pi;
    return angle < 30 ? "flat" : angle <= 60 ? "rift" : "quarter";
}

PartChoice choiceFor(const ModelPart& part, const std::map<std::string, PartChoice>& choices) {
    auto own = choices.find(part.name);
    if (own != choices.end()) return own->second;
    auto panel = part.panel.empty() ? choices.end() : choices.find(part.panel);
    if (panel == choices.end()) return {};
    PartChoice c = panel->second;
    if (c.seed) *c.seed += uint64_t(std::max(0, part.panelBoard - 1));
    return c;
}

PartFrame plannedFrame(const ModelPart& part, const PartChoice& choice) {
    if (choice.fibre) return partFrameAlong(part.mesh, *choice.fibre);
    if (part.panelFibre) return partFrameAlong(part.mesh, *part.panelFibre);
    return partFrame(part.mesh);
}

std::vector<PartPlan> planFurniture(const std::vector<ModelPart>& parts,
                                    const FurniturePlanRequest& request, TreeCache& trees) {
    std::vector<PartPlan> plan;
    for (size_t i = 0; i < parts.size(); ++i) {
        const ModelPart& part = parts[i];
        PartPlan p;
        p.name = part.name;
        p.material = part.material;
        p.panel = part.panel;
        p.triangles = part.mesh.triangles.size();
        const PartChoice choice = choiceFor(part, request.choices);
        auto byMaterial = request.grainByMaterial.find(part.material);
        p.grain = choice.grain                                  ? *choice.grain
                  : byMaterial != request.grainByMaterial.end() ? byMaterial->second
                                                                : request.grain;
        p.frame = plannedFrame(part, choice);
        p.seed = choice.seed.value_or(i);
        p.requested = choice.sawing.value_or(request.cut.sawing);
        p.wood = choice.wood.value_or(true);
        if (p.wood && !(part.area > 0)) {
            p.wood = false;
            p.notes.push_back("no area (every triangle degenerate): left out of the wood");
        }
        if (p.wood) {
            const GrownTree& tree = trees.tree(request.skeleton, p.grain);
            cutPartBoard(p, tree.field(), request.cut);
            if (!p.board)
                throw InputError(
                    "part " + p.name, "",
                    fmt::format("no board of {:.3g} x {:.3g} x {:.3g} m fits in the log even "
                                "{} times narrowed: a larger tree (skeleton, felling time) or "
                                "a smaller --unit",
                                p.frame.extent.x, p.frame.extent.y, p.frame.extent.z, kNarrowings));
        }
        plan.push_back(std::move(p));
    }
    return plan;
}

nlohmann::json planJson(const std::vector<PartPlan>& plan) {
    auto vec = [](const Vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); };
    nlohmann::json parts = nlohmann::json::array();
    for (const PartPlan& p : plan) {
        nlohmann::json j = {{"name", p.name},
                            {"material", p.material},
                            {"triangles", p.triangles},
                            {"wood", p.wood},
                            {"fibre", vec(p.frame.axes[0])},
                            {"width_axis", vec(p.frame.axes[1])},
                            {"size", vec(p.frame.extent)},
                            {"seed", p.seed}};
        if (!p.panel.empty()) j["panel"] = p.panel;
        if (p.wood) {
            j["grain"] = p.grain;
            j["sawing"] = p.sawing;
            j["requested_sawing"] = sawingName(p.requested);
            if (p.board) {
                const BoardCut& b = *p.board;
                j["board"] = {{"height", b.height},
                              {"azimuth_degrees", b.azimuth * 180 / std::numbers::pi},
                              {"offset", b.offset},
                              {"width", p.boardWidth},
                              {"quarter_sawn", b.quarterSawn},
                              {"tint", {b.tint.r, b.tint.g, b.tint.b}}};
                const RigidTransform& t = p.treeFromModel;
                j["tree_from_model"] = {
                    {"x", vec(t.x)}, {"y", vec(t.y)}, {"z", vec(t.z)}, {"origin", vec(t.origin)}};
            }
        }
        if (!p.notes.empty()) j["notes"] = p.notes;
        parts.push_back(std::move(j));
    }
    return parts;
}

PlanChoices readPlanChoices(const std::string& file) {
    const nlohmann::json json = parseJsonFile(file);
    JsonReader root(json, file);
    PlanChoices plan;
    if (const nlohmann::json* grains = root.raw("grain_by_material")) {
        if (!grains->is_object())
            throw root.error("grain_by_material",
                             "expected an object: material name -> grain file");
        for (const auto& [material, grain] : grains->items()) {
            if (!grain.is_string())
                throw root.error("grain_by_material",
                                 fmt::format("\"{}\": expected a grain file name", material));
            plan.grainByMaterial[material] = pathRelativeTo(file, grain.get<std::string>());
        }
    }
    std::map<std::string, PartChoice>& choices = plan.parts;
    for (JsonReader& r : root.objectList("parts")) {
        if (!r.has("name")) throw r.error("name", "missing: the part's name");
        const std::string name = r.string("name", "");
        PartChoice c;
        if (r.has("wood")) c.wood = r.boolean("wood", true);
        if (r.has("grain")) c.grain = pathRelativeTo(file, r.string("grain", ""));
        if (r.has("fibre")) {
            const Vec3 f = r.vec3("fibre", {});
            if (!(length(f) > 1e-9)) throw r.error("fibre", "expected a direction, not zero");
            c.fibre = normalize(f);
        }
        if (r.has("requested_sawing"))
            c.sawing = parseSawing(r, "requested_sawing", r.string("requested_sawing", ""));
        if (r.has("seed")) c.seed = static_cast<uint64_t>(r.integer("seed", 0, 0, 1ll << 53));
        if (!choices.emplace(name, c).second)
            throw r.error("name", fmt::format("\"{}\": a second part of that name", name));
    }
    return plan;
}

}  // namespace nenrin
