#pragma once
/// Normals for a model that has none: smooth across the gentle angles of a turned leg's
/// facets, sharp at a board's edges (the "auto smooth" of modelling tools). A part without
/// normals would otherwise be flat-shaded by the renderer, and every output of
/// `nenrin furniture` (the parts' OBJ files, the glTF, the bakes) must shade it alike.

#include "renderer/geometry/obj_mesh.h"

namespace nenrin {

/// Faces meeting at less than this angle (degrees) share their normals.
inline constexpr double kCreaseAngle = 40;

/// The mesh with a normal per corner: the angle-weighted mean of the normals of the triangles
/// round the corner's position (equal positions count as one vertex) that lie within
/// `creaseDegrees` of the corner's own triangle. Vertices are split where their corners'
/// normals differ; uvs and labels are kept. Zero-area triangles take a neighbour's normal, or
/// (0, 0, 1).
TriangleMesh withCreaseNormals(const TriangleMesh& mesh, double creaseDegrees = kCreaseAngle);

}  // namespace nenrin
