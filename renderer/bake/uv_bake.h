#pragma once
/// Baking a wood object onto its mesh's UV layout: for every texel a triangle covers, the
/// surface point, its shading frame (tangent along +u, bitangent along +v, the normal) and the
/// wood material evaluated there, filtered over the texel's footprint on the surface (the ring
/// prefilter with dP/du / W and dP/dv / H as the footprint). Then gutter padding past the UV
/// seams. The maps are described in docs/uv-bake.md.

#include <map>
#include <string>
#include <vector>

#include "renderer/bake/uv_raster.h"
#include "renderer/scene.h"

namespace nenrin {

struct UvBakeOptions {
    int width = 2048, height = 2048;
    int padding = 8;  ///< texels of gutter grown past every chart's edge
    int threads = 0;
    bool quiet = false;
};

/// The baked maps, row 0 at the top (v = 1), each row-major.
struct UvMaps {
    int width = 0, height = 0;
    std::vector<float>
        baseColour;  ///< RGBA: scene-linear albedo, A = texel covered (before padding)
    std::vector<float> roughness;  ///< 1 channel: GGX alpha of the finish
    std::vector<float>
        normal;                ///< RGB: tangent-space normal from the late-wood relief, 0.5 n + 0.5
    std::vector<float> fibre;  ///< RGB: tangent-space fibre direction, 0.5 f + 0.5
    std::vector<float> growth;  ///< 2 channels: T (years), knot (0..1)
    UvRaster raster;            ///< coverage, overlaps, uvs outside [0,1]
};

/// Bakes `object` (a mesh with uvs and a wood material) of `scene`. Throws InputError if the
/// object is not such a mesh.
UvMaps bakeUvMaps(const Scene& scene, const SceneObject& object, const UvBakeOptions& options);

/// Writes the maps as linear EXR into `folder` (basecolor.exr, roughness.exr, normal.exr,
/// fibre.exr, growth.exr), the mesh as NAME.obj with NAME.mtl pointing at them. Every file is
/// written to a temporary name first. Returns the files written.
std::vector<std::string> writeUvMaps(const UvMaps& maps, const SceneObject& object,
                                     const std::string& folder,
                                     const std::map<std::string, std::string>& metadata);

}  // namespace nenrin
