#pragma once
/// A UV texture set as glTF 2.0 (docs/uv-bake.md): NAME.gltf with NAME.bin and PNG textures,
/// and the same as one NAME.glb. The mesh with normals and uvs; the material as
/// pbrMetallicRoughness (base colour sRGB, roughness in G of the metallic-roughness texture,
/// metallic 0), the tangent-space normal map, the finish's coat as KHR_materials_clearcoat and
/// the fibres as KHR_materials_anisotropy (direction in RG, strength in B).

#include <map>
#include <string>
#include <vector>

#include "renderer/scene.h"
#include "renderer/texture_set/uv_bake.h"

namespace nenrin {

/// Writes basecolor.png, metallic-roughness.png, normal.png, anisotropy.png (not for a finish
/// without a fibre highlight), NAME.gltf, NAME.bin and NAME.glb into `folder` (which must exist),
/// each under a temporary name until all are complete. Returns the files written.
std::vector<std::string> writeGltfTextureSet(const UvMaps& maps, const SceneObject& object,
                                             const std::string& folder,
                                             const std::map<std::string, std::string>& metadata);

}  // namespace nenrin
