#pragma once
/// The files of a UV texture set (docs/uv-bake.md): the maps as linear EXR, the mesh as OBJ with
/// an MTL whose PBR keys open it with its coat in current importers, and texture-set.json, the
/// machine-readable description (maps, encodings, the finish's constants) that the Blender
/// add-on reads.

#include <map>
#include <string>
#include <vector>

#include "renderer/scene.h"
#include "renderer/texture_set/uv_bake.h"

namespace nenrin {

/// The OBJ/MTL/glTF file stem for an object: its name with every character other than letters,
/// digits, '-' and '_' replaced by '_'.
std::string textureSetStem(const std::string& objectName);

/// Writes basecolor.exr, coverage.exr, roughness.exr, normal.exr, fibre.exr, growth.exr,
/// NAME.obj, NAME.mtl and texture-set.json into `folder` (which must exist). Every file is
/// written under a temporary name and renamed only when all are complete. Returns the files.
std::vector<std::string> writeTextureSet(const UvMaps& maps, const SceneObject& object,
                                         const std::string& folder,
                                         const std::map<std::string, std::string>& metadata);

}  // namespace nenrin
