#pragma once
/// A glTF 2.0 model of one or more meshes, each a node of the default scene with its own
/// material, written as NAME.gltf + NAME.bin (images by their file names) and as one NAME.glb
/// (images embedded). A textured node's material is a baked texture set (docs/uv-bake.md):
/// pbrMetallicRoughness (base colour sRGB, roughness in G of the metallic-roughness texture,
/// metallic 0), the tangent-space normal map, the finish's coat as KHR_materials_clearcoat and
/// the fibres as KHR_materials_anisotropy (direction in RG, strength in B). A plain node's is a
/// base colour factor.

#include <string>
#include <vector>

#include "grain/rgb.h"
#include "renderer/geometry/obj_mesh.h"
#include "renderer/texture_set/folder_outputs.h"
#include "renderer/texture_set/pbr_finish.h"

namespace nenrin {

struct GltfNode {
    std::string name;
    const TriangleMesh* mesh = nullptr;  ///< a textured node's must have uvs
    std::string materialName;
    /// A texture set: indices into the model's images of its base colour, metallic-roughness,
    /// normal and anisotropy maps (the last -1 without a fibre highlight). -1: a plain node.
    int images[4] = {-1, -1, -1, -1};
    PbrFinish finish;              ///< a textured node's
    Rgb colour{0.45, 0.45, 0.45};  ///< a plain node's base colour (linear)
    bool textured() const { return images[0] >= 0; }
};

/// An image of the model: its file name in NAME.gltf (relative to it) and its PNG bytes.
struct GltfImage {
    std::string uri;
    std::vector<unsigned char> png;
};

/// Writes NAME.gltf, NAME.bin and NAME.glb through `out` (under temporary names until the
/// caller commits). Throws InputError naming the file when one cannot be written.
void writeGltfModel(const std::vector<GltfNode>& nodes, const std::vector<GltfImage>& images,
                    const std::string& stem, const std::string& generator, FolderOutputs& out);

}  // namespace nenrin
