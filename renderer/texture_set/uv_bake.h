#pragma once
/// Baking a wood object onto its mesh's UV layout: for every texel a triangle covers, the
/// surface point, its shading frame (tangent along +u, bitangent along +v, the normal) and the
/// wood material evaluated there, filtered over the texel's footprint on the surface (the ring
/// prefilter with dP/du / W and dP/dv / H as the footprint). Then gutter padding past the UV
/// seams. The maps are described in docs/uv-bake.md.

#include <vector>

#include "renderer/scene.h"
#include "renderer/texture_set/uv_raster.h"
#include "shader/finish.h"

namespace nenrin {

struct UvBakeOptions {
    int width = 2048, height = 2048;
    int padding = 8;  ///< texels of gutter grown past every chart's edge
    int threads = 0;
    bool quiet = false;
};

/// The baked maps, row 0 at the top (v = 1), each row-major. Every texel holds a meaningful
/// value: covered ones the wood, the gutter their neighbours' mean, the rest neutral values
/// (the mean wood colour, a flat normal, a fibre along +u).
struct UvMaps {
    int width = 0, height = 0;
    std::vector<float> baseColour;  ///< RGB: scene-linear albedo (opaque)
    std::vector<float> coverage;    ///< 1 channel: 1 on texels a triangle covers, else 0
    /// 1 channel: perceptual roughness of the base's specular lobe (renderer/texture_set/
    /// pbr_finish.h); the coat's is a constant of the finish.
    std::vector<float> roughness;
    std::vector<float> normal;  ///< RGB: tangent-space normal from the relief, 0.5 n + 0.5
    std::vector<float> fibre;   ///< RGB: tangent-space fibre direction, 0.5 f + 0.5
    std::vector<float> growth;  ///< 2 channels: T (years), knot (0..1)
    Finish finish;              ///< of the wood material: the constants of the set
    UvRaster raster;            ///< coverage, overlaps, uvs outside [0,1]
};

/// Bakes `object` (a mesh with uvs and a wood material) of `scene`. Throws InputError if the
/// object is not such a mesh.
UvMaps bakeUvMaps(const Scene& scene, const SceneObject& object, const UvBakeOptions& options);

}  // namespace nenrin
