#include "renderer/direct_light.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace nenrin {

namespace {

/// A shadow ray's extent towards a light at infinity.
constexpr double kDistantReach = 1e30;

}  // namespace

DirectLight::DirectLight(const Scene& scene)
    : scene_(scene),
      env_(environmentLight(scene)),
      selection_(scene.lights, scene.settings.lightSelection) {}

void DirectLight::sample(const LitVertex& v, const BounceRandom& random,
                         std::span<BsdfValue> distantValues, uint32_t path,
                         std::vector<ShadowRay>& out) {
    if (!(v.woLocal.z > 0)) return;
    const SurfaceBsdf& bsdf = v.surface->bsdf;
    const AxisFrame& frame = v.surface->frame;
    const std::vector<uint32_t>& everyVertex = selection_.everyVertex();
    size_t picked = scene_.lights.size();
    double pickedProbability = 1;
    if (selection_.picksOne())
        picked =
            selection_.select(v.position, v.ng, random.at(dimension::lightPick(everyVertex.size())),
                              pickedProbability, cdf_);
    const size_t sampled = everyVertex.size() + (picked < scene_.lights.size());
    // One light's sample: its shadow ray towards `direction`, carrying the throughput times
    // f x radiance x cos / pdf (litF) and its diffuse part.
    auto addShadowRay = [&](const Vec3& direction, double tMax, const Rgb& litF,
                            const Rgb& litDiffuse) {
        const Rgb contribution = multiply(v.throughput, litF);
        const Rgb diffuse =
            v.camera ? multiply(v.throughput, litDiffuse) : multiply(v.diffuseShare, contribution);
        out.push_back({path,
                       {offsetOrigin(v.position, v.ng, direction), direction},
                       tMax,
                       contribution,
                       diffuse,
                       false,
                       v.camera});
    };
    for (size_t k = 0; k < sampled; ++k) {
        const size_t li = k < everyVertex.size() ? everyVertex[k] : picked;
        const double selected = k < everyVertex.size() ? 1 : pickedProbability;
        const Light& light = scene_.lights[li];
        // Shared only towards distant lights, whose direction is the same for every sample;
        // other lights are sampled per sample, and their pdf goes with their own f.
        const bool shareLight = !distantValues.empty() && light.type == LightType::Distant;
        if (shareLight && selected == 1 && distantValues[li].lit) {
            const BsdfValue& kept = distantValues[li];
            addShadowRay(light.direction, kDistantReach, kept.litF, kept.litDiffuse);
            continue;
        }
        LightSample ls;
        // Delta lights take no sample: their numbers are not drawn (a hash each, per sample).
        const bool delta = light.type == LightType::Distant || light.type == LightType::Point;
        const auto [u1, u2] =
            delta ? std::pair<double, double>{0, 0} : random.pair(dimension::lightPair(k));
        if (!sampleLight(light, v.position, u1, u2, ls) || dot(ls.direction, v.ng) <= 0) continue;
        Vec3 wiLocal = frame.toLocal(ls.direction);
        BsdfValue value;
        if (shareLight && distantValues[li].f.r >= 0) {
            value = distantValues[li];
        } else {
            value.f = bsdf.evaluate(v.woLocal, wiLocal, value.diffuse);
            if (shareLight) distantValues[li] = value;
        }
        const Rgb& f = value.f;
        if (isBlack(f) || isBlack(ls.radiance)) continue;
        const double tMax = std::isinf(ls.distance) ? kDistantReach : ls.distance * (1 - 1e-4);
        // MIS only if BSDF sampling can also find this light (not at the last vertex).
        const double pdf = ls.pdf * selected;
        double weight =
            ls.delta || !v.continues ? 1 : powerHeuristic(pdf, bsdf.pdf(v.woLocal, wiLocal));
        const double scale = wiLocal.z * weight / pdf;
        const Rgb litF = multiply(f, ls.radiance) * scale;
        const Rgb litDiffuse = multiply(value.diffuse, ls.radiance) * scale;
        if (shareLight && selected == 1) {
            distantValues[li].lit = true;
            distantValues[li].litF = litF;
            distantValues[li].litDiffuse = litDiffuse;
        }
        addShadowRay(ls.direction, tMax, litF, litDiffuse);
    }
}

void traceShadowRays(const RayScene& rays, std::span<ShadowRay> shadows) {
    constexpr size_t kStride = sizeof(ShadowRay);
    for (size_t base = 0; base < shadows.size(); base += 16) {
        int count = static_cast<int>(std::min<size_t>(16, shadows.size() - base));
        ShadowRay& first = shadows[base];
        rays.occluded16({&first.ray, kStride}, {&first.tMax, kStride}, count,
                        {&first.blocked, kStride});
    }
}

}  // namespace nenrin
