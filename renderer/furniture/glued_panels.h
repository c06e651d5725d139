#pragma once
/// Panels glued from several boards: a wood part wider than one board from a log would be
/// (a seat, a table top, a cabinet side) is made, as a joiner makes it, of boards edge-glued
/// side by side. The part's mesh is cut across its width into equal strips, each strip then a
/// part of its own (its own board from the cut plan) that keeps the panel's fibre direction.

#include <map>
#include <string>
#include <vector>

#include "renderer/furniture/furniture_plan.h"
#include "renderer/furniture/model_parts.h"

namespace nenrin {

/// The widest board a panel is glued from (m): joiners glue panels from boards 10-20 cm wide,
/// which stay flat as they dry and shrink.
inline constexpr double kWidestBoard = 0.2;

/// The part of `mesh` with lo <= dot(p - origin, axis) <= hi: triangles crossing either plane
/// are clipped (normals and uvs interpolated); vertices shared before stay shared.
TriangleMesh clipToSlab(const TriangleMesh& mesh, const Vec3& origin, const Vec3& axis, double lo,
                        double hi);

/// Every part that is wood (by `choices`, by the panel's name) and wider than kWidestBoard
/// replaced by ceil(width / kWidestBoard) strips across its width, named "NAME/board-K", with
/// `panel` = NAME and `panelFibre` = the panel's fibre. Other parts are kept as they are.
std::vector<ModelPart> glueWidePanels(std::vector<ModelPart> parts,
                                      const std::map<std::string, PartChoice>& choices);

}  // namespace nenrin
