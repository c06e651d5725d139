#pragma once
/// Triangle meshes from glTF 2.0 files (.gltf with its .bin, or .glb), read with tinygltf.

#include <string>

#include "renderer/geometry/obj_mesh.h"

namespace nenrin {

/// Loads every triangle primitive the default scene (else the first scene, else every mesh)
/// places, with its node transforms applied, as one mesh: positions, NORMAL if every primitive
/// has it, TEXCOORD_0 if every primitive has it (v flipped to OBJ's convention, v = 0 at the
/// bottom of the image). Points and lines are ignored. Throws InputError naming the file and
/// the mesh/primitive/accessor for a parse error, a missing or short buffer, an accessor of the
/// wrong type, non-finite values, indices out of range, sparse accessors, or no triangles.
/// Images are not decoded; buffers must be files next to the glTF, inside the GLB, or data URIs.
/// With `nodeName`, only the meshes of every node of that name and its children
/// (InputError if the scene has none).
TriangleMesh loadGltfMesh(const std::string& path, const std::string& nodeName = "");

/// True if `path` ends in .gltf or .glb (any case).
bool isGltfPath(const std::string& path);

}  // namespace nenrin
