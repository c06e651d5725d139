#pragma once
/// Direct light: next-event estimation at a path vertex, and the densities multiple importance
/// sampling weighs a BSDF-sampled ray that finds a light by itself against. At every vertex one
/// sample of each light LightSelection samples there (with a few lights all of them: far less
/// noisy than picking one of a sun and a sky at random), and with many local lights one more,
/// picked by its importance there, its sample divided by the odds of picking it. Each sample
/// becomes a shadow ray; the rays of a bounce are traced together, in packets.

#include <cstdint>
#include <span>
#include <vector>

#include "grain/rgb.h"
#include "renderer/light_selection.h"
#include "renderer/lights.h"
#include "renderer/material_bsdf.h"
#include "renderer/ray_scene.h"
#include "renderer/sample_dimensions.h"
#include "renderer/scene.h"

namespace nenrin {

/// The multiple importance sampling weight of a sample drawn with density a against another
/// strategy's density b.
inline double powerHeuristic(double a, double b) {
    double a2 = a * a, b2 = b * b;
    return a2 + b2 > 0 ? a2 / (a2 + b2) : 0;
}

/// One light sample of a path vertex, waiting for its shadow ray.
struct ShadowRay {
    uint32_t path;  ///< the path's index in its bounce
    Ray ray;
    double tMax;
    Rgb contribution;  ///< throughput x light sample: added to the path if nothing blocks it
    Rgb diffuse;       ///< the part of it the first hit's albedo carries (the film's diffuse)
    bool blocked = false;
    bool camera = false;  ///< made at the camera ray's hit (the film's visibility AOV counts it)
};

/// A path vertex on a surface, as next-event estimation sees it.
struct LitVertex {
    Vec3 position;
    Vec3 ng;  ///< geometric normal, on the side the path came from
    const SurfaceShading* surface = nullptr;
    Vec3 woLocal;  ///< back along the path, in surface->frame
    Rgb throughput;
    /// Per channel, the share of the throughput that left the first hit by its diffuse part
    /// (PathState::diffuseShare); at the camera's hit the BSDF's own split is used instead.
    Rgb diffuseShare;
    bool camera = false;     ///< the camera ray's hit
    bool continues = false;  ///< the path may bounce again, so BSDF sampling may find a light
};

/// The BSDF's value towards a light, and its diffuse part (SurfaceBsdf::evaluate).
struct BsdfValue {
    Rgb f, diffuse;
    /// Once a sample of a distant light taken with odds 1 has lit the vertex: f and diffuse
    /// times the light's radiance and cos theta_i (what each sample's throughput multiplies),
    /// so the samples that share the vertex only trace their shadow rays.
    bool lit = false;
    Rgb litF, litDiffuse;
};

class DirectLight {
public:
    /// `scene` must outlive this.
    explicit DirectLight(const Scene& scene);

    /// Appends the shadow rays of next-event estimation at `v` (path `path`) to `out`, in light
    /// order; none if wo is below the shading surface. `distantValues`, one per scene light:
    /// the BSDF's values towards the distant ones, shared by samples with the same BSDF and (up
    /// to a pixel's spread) the same wo; f.r < 0: not known yet; once `lit`, a later sample
    /// takes the lit value and only adds its own shadow ray. Empty: nothing shared.
    void sample(const LitVertex& v, const BounceRandom& random, std::span<BsdfValue> distantValues,
                uint32_t path, std::vector<ShadowRay>& out);

    // Inline: every path that leaves the scene or finds a light asks (MIS).

    /// Radiance from the environment along a ray that leaves the scene (black without one).
    Rgb environmentRadiance(const Vec3& direction) const {
        return env_ ? env_->environment->radiance(direction) : Rgb{};
    }
    /// Density (solid angle) with which next-event estimation at (from, fromNormal) samples
    /// `direction` on the environment, selection included.
    double environmentPdf(const Vec3& direction, const Vec3& from, const Vec3& fromNormal) const {
        if (!env_) return 0;
        return env_->environment->pdf(direction) *
               selection_.probability(static_cast<size_t>(env_ - scene_.lights.data()), from,
                                      fromNormal);
    }
    /// Density (solid angle) with which next-event estimation at (from, fromNormal) samples the
    /// point at `distance` along `direction` on rectangle light `light`, selection included.
    double rectPdf(uint32_t light, const Vec3& direction, double distance, const Vec3& from,
                   const Vec3& fromNormal) const {
        return rectLightPdf(scene_.lights[light], direction, distance) *
               selection_.probability(light, from, fromNormal);
    }

private:
    const Scene& scene_;
    const Light* env_;
    LightSelection selection_;
    std::vector<double> cdf_;  ///< LightSelection::select's scratch
};

/// Traces the shadow rays in 16-ray packets and marks the blocked ones.
void traceShadowRays(const RayScene& rays, std::span<ShadowRay> shadows);

}  // namespace nenrin
