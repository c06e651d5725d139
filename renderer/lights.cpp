#include "renderer/lights.h"

#include <cmath>
#include <limits>

namespace nenrin {

bool sampleLight(const Light& l, const Vec3& p, double u1, double u2, LightSample& s) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    switch (l.type) {
        case LightType::Distant:
            s = {l.direction, l.power, 1, kInf, true};
            return true;
        case LightType::Point: {
            Vec3 d = l.position - p;
            double d2 = lengthSquared(d);
            if (!(d2 > 0)) return false;
            double dist = std::sqrt(d2);
            s = {d / dist, l.power * (1 / d2), 1, dist, true};
            return true;
        }
        case LightType::Rect: {
            Vec3 q = l.corner + l.edgeU * u1 + l.edgeV * u2;
            Vec3 d = q - p;
            double d2 = lengthSquared(d);
            if (!(d2 > 0)) return false;
            double dist = std::sqrt(d2);
            Vec3 w = d / dist;
            double cosLight = -dot(w, l.normal);
            if (cosLight <= 0) return false;  // one-sided: p is behind the light
            s = {w, l.power, d2 / (l.area * cosLight), dist, false};
            return true;
        }
        case LightType::Environment: {
            EnvironmentMap::Sample e = l.environment->sample(u1, u2);
            if (!(e.pdf > 0)) return false;
            s = {e.direction, e.radiance, e.pdf, kInf, false};
            return true;
        }
    }
    return false;
}

Rgb rectLightRadiance(const Light& l, const Vec3& direction) {
    return dot(direction, l.normal) < 0 ? l.power : Rgb{};
}

double rectLightPdf(const Light& l, const Vec3& direction, double distance) {
    double cosLight = -dot(direction, l.normal);
    if (cosLight <= 0) return 0;
    return distance * distance / (l.area * cosLight);
}

const Light* environmentLight(const Scene& scene) {
    for (const Light& l : scene.lights)
        if (l.type == LightType::Environment) return &l;
    return nullptr;
}

}  // namespace nenrin
