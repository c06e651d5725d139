#pragma once
/// `nenrin furniture` as a job: a model (OBJ or glTF) cut into parts, every wood part its own
/// board from the log (renderer/furniture), written as parts.json (the plan, editable and read
/// back with --plan), the parts as OBJ files in metres, scene.json (the model in solid wood, a
/// camera framing it), preview.png rendered from it, and every wood part's texture set (glTF
/// with PNG maps, baked on its uvs). All outputs or none.

#include <map>
#include <string>
#include <vector>

#include "renderer/geometry/rigid_transform.h"

namespace nenrin {

struct FurnitureJob {
    std::string model;
    std::string grain;
    std::string skeleton;  ///< empty: the bundled straight trunk
    std::string output;    ///< folder
    std::string unit = "m";
    std::string plan;  ///< a parts.json to re-do the job with
    /// Grain file per material name (--grain-for), over the plan's `grain_by_material`.
    std::map<std::string, std::string> grainByMaterial;
    std::vector<std::string> grainFor;  ///< the command line's MATERIAL=FILE pairs
    std::string sawing = "mixed";
    std::string finish = "oiled";  ///< a finish preset of the wood (docs/scene-format.md)
    long long seed = 1;
    int textureSize = 1024;  ///< texels of each part's texture set; 0 = none
    int previewWidth = 640, previewHeight = 480, previewSpp = 32;
    int threads = 0;
    bool quiet = false;
};

struct FurnitureReport {
    std::vector<std::string> written;
    std::vector<std::string> warnings;
    size_t parts = 0, woodParts = 0;
};

FurnitureReport runFurnitureJob(const FurnitureJob& job);

/// Metres per model unit for "mm", "cm" or "m"; InputError at --unit otherwise.
double metresPerUnit(const std::string& unit);

/// The x, y, z angles (degrees) of a scene's `log.rotate` that give `treeFromObject`'s
/// rotation (scene-format.md: the object turned about x, then y, then z, and then stood on the
/// trunk, its +y along the tree's +z).
Vec3 logRotateDegrees(const RigidTransform& treeFromObject);

}  // namespace nenrin
