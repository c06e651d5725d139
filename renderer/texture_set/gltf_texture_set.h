#pragma once
/// A UV texture set as glTF 2.0 (docs/uv-bake.md): NAME.gltf with NAME.bin and PNG textures,
/// and the same as one NAME.glb: the mesh with normals and uvs, its material the baked maps
/// (renderer/texture_set/gltf_model.h says how they map onto glTF's).

#include <map>
#include <string>
#include <vector>

#include "renderer/scene.h"
#include "renderer/texture_set/gltf_model.h"
#include "renderer/texture_set/uv_bake.h"

namespace nenrin {

/// What writeGltfTextureSet wrote: the files, and the PNGs (name, bytes) and finish again
/// for a model of several parts that shows this set (renderer/texture_set/gltf_model.h).
struct GltfTextureSet {
    std::vector<std::string> written;
    std::vector<GltfImage> images;  ///< base colour, metallic-roughness, normal[, anisotropy]
    PbrFinish finish;
};

/// Writes basecolor.png, metallic-roughness.png, normal.png, anisotropy.png (not for a finish
/// without a fibre highlight), NAME.gltf, NAME.bin and NAME.glb into `folder` (which must exist),
/// each under a temporary name until all are complete.
GltfTextureSet writeGltfTextureSet(const UvMaps& maps, const SceneObject& object,
                                   const std::string& folder,
                                   const std::map<std::string, std::string>& metadata);

}  // namespace nenrin
