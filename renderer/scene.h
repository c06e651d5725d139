#pragma once
/// A loaded scene: camera, render settings, lights, materials, objects, and the trees their
/// wood comes from. Built by loadScene (scene_file.h) from the JSON described in
/// docs/scene-format.md; immutable while rendering.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "grain/grown_tree.h"
#include "renderer/environment_map.h"
#include "renderer/geometry/obj_mesh.h"
#include "renderer/geometry/rigid_transform.h"
#include "renderer/image_texture.h"
#include "renderer/products/laminated_product.h"
#include "shader/wood_shader.h"

namespace nenrin {

struct CameraSpec {
    Vec3 position{0, 1, 3};
    Vec3 lookAt{0, 0, 0};
    Vec3 up{0, 1, 0};
    double verticalFov = radians(40);  ///< radians
    double apertureRadius = 0;         ///< m: 0 = pinhole
    double focusDistance = 0;          ///< m: 0 = distance to lookAt
};

/// Next-event estimation: every light at every vertex, or the sun and sky at every vertex and
/// one of the point and rectangle lights picked by its importance there
/// (renderer/light_selection.h); auto picks past 2 point and rectangle lights.
enum class LightSelectionMode { Auto, All, Importance };

struct RenderSettings {
    int width = 640, height = 400;
    int spp = 16;      ///< samples per pixel; with adaptive sampling, the most a pixel takes
    int maxDepth = 6;  ///< path vertices after the camera
    uint64_t seed = 1;
    /// Adaptive sampling (0 = off: every pixel takes spp samples). A pixel stops once its
    /// estimated standard error over the square root of its level (summed over R, G, B; pooled
    /// over its 3 x 3 neighbourhood) is at most this (docs/render.md#adaptive-sampling).
    double noiseThreshold = 0;
    int minSpp = 0;  ///< samples every pixel takes before the first estimate; 0 = min(spp, 16)
    LightSelectionMode lightSelection = LightSelectionMode::Auto;
};

enum class LightType { Distant, Point, Rect, Environment };

struct Light {
    LightType type = LightType::Distant;
    /// Distant: irradiance on a surface facing it (W/m^2 per channel); point: intensity
    /// (W/sr); rect: emitted radiance (one-sided, along normal).
    Rgb power;
    Vec3 direction;                     ///< distant: unit vector towards the light
    Vec3 position;                      ///< point
    Vec3 corner, edgeU, edgeV, normal;  ///< rect: normal = normalize(edgeU x edgeV)
    double area = 0;
    std::shared_ptr<const EnvironmentMap> environment;
};

enum class MaterialType { Diffuse, Glossy, Metal, Wood, Textured };

struct Material {
    std::string name;
    MaterialType type = MaterialType::Diffuse;
    Rgb colour{0.7, 0.7, 0.7};
    double roughness = 0.2;            ///< GGX alpha of the coat / metal
    const WoodShader* wood = nullptr;  ///< wood only
    /// Textured (baked wood maps read back, docs/uv-bake.md): base colour, and optionally
    /// tangent-space normal and fibre maps (or a glTF anisotropy map instead of the fibre
    /// map: direction across the fibres in RG, strength in B), under `finish`.
    std::shared_ptr<const ImageTexture> baseColourMap, normalMap, fibreMap, anisotropyMap;
    Finish finish;
};

/// A skeleton with its grain: the tree every wood material of that pair cuts from.
struct WoodTree {
    std::string skeletonFile, grainFile;
    std::unique_ptr<const GrownTree> grown;
};

enum class ShapeType { Box, Mesh };

struct SceneObject {
    std::string name;
    std::string type;  ///< as in the file: box, mesh, glulam, clt, table_top
    ShapeType shape = ShapeType::Box;
    RigidTransform worldFromObject;
    Vec3 size;  ///< box: full extents in object space
    std::shared_ptr<const TriangleMesh> mesh;
    uint32_t material = 0;
    /// Wood: laminated products map each lamella on its own; other objects use treeFromObject.
    std::shared_ptr<const LaminatedLayout> layout;
    RigidTransform treeFromObject;
    /// Solid wood: the board's tree, a filter on the albedo (scene `log.tint`; lamellae have
    /// their own).
    Rgb boardTint{1, 1, 1};
};

struct Scene {
    std::string file;
    /// The scene JSON as loaded (after overrides), compact: with inputFiles, what a split
    /// job's fingerprint is made of.
    std::string source;
    /// Every file the scene refers to (skeletons, grain files, meshes, textures, maps).
    std::vector<std::string> inputFiles;
    CameraSpec camera;
    RenderSettings settings;
    std::vector<Light> lights;
    std::vector<Material> materials;
    std::vector<std::unique_ptr<WoodTree>> trees;
    std::vector<std::unique_ptr<WoodShader>> woodShaders;
    std::vector<SceneObject> objects;
};

}  // namespace nenrin
