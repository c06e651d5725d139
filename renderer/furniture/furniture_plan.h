#pragma once
/// The cut plan of a piece of furniture: every wood part its own board, drawn from the log by
/// the sawmill of the laminated products (products/cut_plan.h) with the part's own seed, the
/// board's length along the part's fibre (its longest principal axis), its width across the
/// part's wide face. The plan is written as parts.json and read back (--plan) with a user's
/// changes: the fibre turned, another species, a part that is not wood, another seed or sawing.

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "grain/grown_tree.h"
#include "renderer/furniture/model_parts.h"
#include "renderer/furniture/part_frame.h"
#include "renderer/products/cut_plan.h"

namespace nenrin {

/// What a user may change per part in parts.json (absent: nenrin's choice).
struct PartChoice {
    std::optional<bool> wood;
    std::optional<std::string> grain;  ///< a grain file (species preset)
    std::optional<Vec3> fibre;         ///< model space
    std::optional<Sawing> sawing;
    std::optional<uint64_t> seed;
};

struct PartPlan {
    std::string name, material;
    std::string panel;  ///< the glued panel it is a board of ("" if none)
    size_t triangles = 0;
    bool wood = true;
    std::string grain;  ///< the grain file this part's board is cut with
    PartFrame frame;    ///< frame.axes[0] is the fibre
    uint64_t seed = 0;  ///< the board's number in the cut plan
    Sawing requested = Sawing::Mixed;
    std::optional<BoardCut> board;
    std::string sawing;     ///< as cut, from the rings' angle to the wide face: flat, rift, quarter
    double boardWidth = 0;  ///< m: the board cut (narrower than the part if it did not fit)
    RigidTransform treeFromModel;  ///< where each point of the part lies in the log
    std::vector<std::string> notes;
};

struct FurniturePlanRequest {
    std::string skeleton;                                ///< the log's skeleton file
    std::string grain;                                   ///< the default grain file
    std::map<std::string, std::string> grainByMaterial;  ///< species per material name
    CutPlanParams cut;
    std::map<std::string, PartChoice> choices;  ///< by part name (from --plan)
};

/// The trees the plan cuts from, one per grain file, loaded once.
class TreeCache {
public:
    const GrownTree& tree(const std::string& skeleton, const std::string& grain);

private:
    std::map<std::pair<std::string, std::string>, std::unique_ptr<GrownTree>> trees_;
};

/// The user's choices for a part: its own entry of --plan, else its panel's when it is a board
/// of a glued panel (a seed chosen for the panel numbers its boards seed, seed + 1, ...).
PartChoice choiceFor(const ModelPart& part, const std::map<std::string, PartChoice>& choices);

/// A part's frame: its fibre the one the user chose, else its panel's, else its longest
/// principal axis.
PartFrame plannedFrame(const ModelPart& part, const PartChoice& choice);

/// Plans every part. Parts that are not wood or have no area get no board (a note says why).
/// Throws InputError naming the part when a board cannot be cut at all.
std::vector<PartPlan> planFurniture(const std::vector<ModelPart>& parts,
                                    const FurniturePlanRequest& request, TreeCache& trees);

/// "flat", "rift" or "quarter": the angle between the growth rings and the wide face at the
/// board's centre (under 30 degrees, 30-60, over 60).
std::string sawingAsCut(const RigidTransform& treeFromLamella);

/// parts.json (docs/furniture.md).
nlohmann::json planJson(const std::vector<PartPlan>& plan);
/// What a user may change in a parts.json: each part's choices and the grain file per
/// material name (`grain_by_material`). Other keys are read by nobody.
struct PlanChoices {
    std::map<std::string, PartChoice> parts;  ///< by part name (or a glued panel's)
    std::map<std::string, std::string> grainByMaterial;
};
PlanChoices readPlanChoices(const std::string& file);

}  // namespace nenrin
