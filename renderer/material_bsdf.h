#pragma once
/// The material step of shading: from a scene material and what the path found at a hit (the
/// wood evaluated there, the board, the glue line) to the layered BSDF (shader/surface_bsdf.h)
/// in the local frame of the shading normal. Every material kind maps onto the one surface
/// model: wood and baked wood maps set every layer, "diffuse" the base only, "glossy" base and
/// coat, "metal" the conductor.

#include "renderer/products/laminated_product.h"
#include "renderer/ray_scene.h"
#include "renderer/scene.h"
#include "shader/surface_bsdf.h"
#include "shader/wood_shader.h"
#include "util/axis_frame.h"

namespace nenrin {

/// A surface hit as the material step sees it.
struct MaterialHit {
    const SurfaceHit* hit = nullptr;  ///< uv and its derivatives (baked maps)
    Vec3 wo;                          ///< unit, back along the ray
    Vec3 ns;                          ///< the shading normal, on wo's side of the surface
    /// Wood: the wood evaluated at the hit, with world-space directions.
    const WoodSurfaceSample* wood = nullptr;
    Rgb boardTint{1, 1, 1};          ///< wood: the board's tree (cut plan)
    const GlueLine* glue = nullptr;  ///< wood in laminated products
    double glueCover = 0;            ///< share of the footprint on the glue line
    /// Path regularisation: glossy lobes at least this rough.
    double minRoughness = 0;
};

/// The scattering at a surface point.
struct SurfaceShading {
    SurfaceBsdf bsdf;  ///< in `frame`
    Vec3 ns;           ///< the shading normal after bump or normal mapping, facing wo
    AxisFrame frame;   ///< around ns
};

/// The BSDF of `material` at `at`.
SurfaceShading materialBsdf(const Material& material, const MaterialHit& at);

}  // namespace nenrin
