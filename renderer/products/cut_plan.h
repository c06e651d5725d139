#pragma once
/// The sawmill: where in the log each board of a laminated product was cut. Boards are drawn
/// from a seed (the same seed gives the same boards, another seed other boards), each
/// independently of the others: a height window along the trunk, an azimuth about the pith,
/// flat-sawn (wide face tangential to the rings: cathedral figure) or quarter-sawn (wide face
/// radial: straight stripes), a radial offset that keeps all four corners inside the bark, and
/// which face and end are up.

#include <cstdint>
#include <optional>
#include <string>

#include "grain/growth_field.h"
#include "grain/rgb.h"
#include "renderer/geometry/rigid_transform.h"

namespace nenrin {

enum class Sawing { Flat, Quarter, Mixed };

struct CutPlanParams {
    uint64_t seed = 1;
    Sawing sawing = Sawing::Mixed;
    double bottom = 0.3;     ///< m: lowest height of a board's lower end
    double top = 0;          ///< m: highest height of a board's upper end; 0 = 70 % of the trunk
    double maxRadius = 0.3;  ///< m: log radius when the grain has no felling time
    double margin = 0.004;   ///< m: wood kept between a board's corners and the bark
    /// Boards of one product come from different trees, which differ in colour by a few
    /// dE*ab: scale of the per-board tint (1 = about 2-3 dE*ab between boards, 0 = none).
    double colourVariation = 1;
};

struct BoardCut {
    double height = 0;   ///< m: of the board's centre along the trunk
    double azimuth = 0;  ///< radians, of the offset direction about the pith
    double offset = 0;   ///< m: board centre's distance from the pith
    bool quarterSawn = false;
    RigidTransform treeFromLamella;  ///< lamella: length x, width y, thickness z, centred
    Rgb tint{1, 1, 1};               ///< this board's tree: a filter on the wood's albedo
};

/// The tint of board `index`: lightness and warmth drawn from the plan's seed (its own stream,
/// so the cut itself does not change with colourVariation).
Rgb boardTint(const CutPlanParams& params, uint64_t index);

/// Log radius (m) at height z along azimuth `theta` (radians): where T reaches the felling
/// time (bisection on the field), or params.maxRadius without a felling time.
double logRadius(const GrowthField& field, const CutPlanParams& params, double z, double theta);

/// Draws board `index` of `length` x `width` x `thickness` (m). Returns nullopt if no
/// position was found in 64 tries (the board is too big for the log's window).
std::optional<BoardCut> cutBoard(const GrowthField& field, const CutPlanParams& params,
                                 double length, double width, double thickness, uint64_t index);

/// The trunk's height range [first node z, last node z].
void trunkHeightRange(const Skeleton& skeleton, double& lo, double& hi);

}  // namespace nenrin
