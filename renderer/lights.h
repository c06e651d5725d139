#pragma once
/// Sampling the scene's lights from a shading point (next-event estimation) and the densities
/// multiple importance sampling needs when a BSDF-sampled ray finds an emitter by itself.
/// Distant and point lights are delta lights: only next-event estimation sees them.

#include "renderer/scene.h"

namespace nenrin {

struct LightSample {
    Vec3 direction;       ///< unit, from the point towards the light
    Rgb radiance;         ///< arriving along it (irradiance for delta lights)
    double pdf = 0;       ///< solid angle density (1 for delta lights)
    double distance = 0;  ///< to the light (infinity for distant and environment)
    bool delta = false;
};

/// Samples light `light` as seen from point p. False if it cannot light p.
bool sampleLight(const Light& light, const Vec3& p, double u1, double u2, LightSample& out);

/// Radiance a ray leaving along `direction` receives from a rectangle light it hits at
/// `distance`, and the solid-angle pdf with which sampleLight would have chosen it.
Rgb rectLightRadiance(const Light& light, const Vec3& direction);
double rectLightPdf(const Light& light, const Vec3& direction, double distance);

/// The environment light of the scene, or null.
const Light* environmentLight(const Scene& scene);

}  // namespace nenrin
