#pragma once
/// A furniture model cut into its parts: first by the file's own groups (OBJ objects and
/// groups, glTF meshes and primitives), then each group into its connected pieces, so four
/// legs modelled as one object are four parts. Pieces that only touch or interpenetrate stay
/// separate parts (they share no vertex); pieces are joined where they share a vertex position.

#include <optional>
#include <string>
#include <vector>

#include "renderer/geometry/obj_mesh.h"

namespace nenrin {

struct ModelPart {
    std::string name;      ///< the group's name, ".1", ".2", ... when it has several pieces
    std::string material;  ///< the material most of its area uses ("" if none)
    TriangleMesh mesh;     ///< the piece alone, with its own vertices (normals, uvs kept)
    double area = 0;       ///< m² (the model's units squared)
    /// A board of a glued panel (renderer/furniture/glued_panels.h): the panel's name and
    /// fibre; "" and none for a part made of one board.
    std::string panel;
    std::optional<Vec3> panelFibre;
    int panelBoard = 0;  ///< 1, 2, ... across the panel
};

/// The area of one triangle and of a whole mesh (the mesh's units squared).
double triangleArea(const TriangleMesh& m, const std::array<uint32_t, 3>& t);
double surfaceArea(const TriangleMesh& m);

/// At most this many parts: a model with more is refused (a scan, a particle cloud).
inline constexpr size_t kMaxModelParts = 10000;

/// The parts of a loaded model (TriangleMesh labels from loadObjMesh / loadGltfMesh), in the
/// order of their first triangle. Throws InputError (the file, "") past kMaxModelParts.
std::vector<ModelPart> splitModelParts(const TriangleMesh& model, const std::string& file);

/// Loads an OBJ or glTF model and scales it by `metresPerUnit`.
TriangleMesh loadFurnitureModel(const std::string& path, double metresPerUnit);

}  // namespace nenrin
