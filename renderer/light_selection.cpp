#include "renderer/light_selection.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

namespace nenrin {

namespace {

constexpr double kPi = std::numbers::pi;
/// Importances are capped so that a sum over a million lights stays finite.
constexpr double kLargestImportance = 1e300;

/// Point and rectangle lights: the ones picked from, rather than sampled at every vertex.
bool isLocal(LightType type) { return type == LightType::Point || type == LightType::Rect; }

/// The largest cosine to n over a ball of radius r seen from distance `distance` along a unit
/// direction whose cosine to n is `cosCentre`: the direction tilted towards n by the ball's
/// half-angle (a bound, so a light partly above the horizon keeps some importance).
double cosineBound(double cosCentre, double r, double distance) {
    if (r >= distance) return 1;
    double theta = std::acos(std::clamp(cosCentre, -1.0, 1.0)) - std::asin(r / distance);
    return theta <= 0 ? 1 : std::cos(std::min(theta, kPi / 2));
}

/// A point light's importance: intensity (luminance y) x cos / d^2.
double pointImportance(const Vec3& position, double y, const Vec3& p, const Vec3& n) {
    Vec3 d = position - p;
    double d2 = lengthSquared(d);
    if (!(d2 > 0)) return 0;
    double c = dot(d, n);
    if (!(c > 0)) return 0;
    // Right next to the light d^3 underflows: keep the sum finite, the odds sensible.
    return std::min(y * c / (d2 * std::sqrt(d2)), kLargestImportance);
}

}  // namespace

LightSelection::LightSelection(const std::vector<Light>& lights, LightSelectionMode mode)
    : lights_(lights) {
    const auto localCount =
        std::count_if(lights.begin(), lights.end(), [](const Light& l) { return isLocal(l.type); });
    const bool pick = mode == LightSelectionMode::Importance ||
                      (mode == LightSelectionMode::Auto &&
                       static_cast<size_t>(localCount) > kEveryLocalLightUpTo);
    if (!pick) {
        everyVertex_.resize(lights.size());
        std::iota(everyVertex_.begin(), everyVertex_.end(), 0u);
        return;
    }
    for (uint32_t i = 0; i < lights.size(); ++i) {
        const Light& l = lights[i];
        if (isLocal(l.type))
            local_.push_back({l.position, luminance(l.power), i, l.type == LightType::Rect});
        else
            everyVertex_.push_back(i);
    }
}

double LightSelection::importance(const Light& l, const Vec3& p, const Vec3& n) {
    const double y = luminance(l.power);
    switch (l.type) {
        case LightType::Distant: {
            double c = dot(l.direction, n);
            return c > 0 ? y * c : 0;
        }
        case LightType::Point:
            return pointImportance(l.position, y, p, n);
        case LightType::Rect: {
            // One-sided: p behind the plane sees none of it.
            double h = dot(p - l.corner, l.normal);
            if (!(h > 0)) return 0;
            // Below the horizon when every corner is (the rectangle is their convex hull).
            const Vec3 corners[4] = {l.corner, l.corner + l.edgeU, l.corner + l.edgeV,
                                     l.corner + l.edgeU + l.edgeV};
            double above = -1;
            for (const Vec3& c : corners) above = std::max(above, dot(c - p, n));
            if (!(above > 0)) return 0;
            Vec3 d = l.corner + (l.edgeU + l.edgeV) * 0.5 - p;
            double d2 = lengthSquared(d);
            double dist = std::sqrt(d2);
            double halfDiagonal = 0.5 * length(l.edgeU + l.edgeV);
            double solidAngle = dist > 0 ? std::min(2 * kPi, l.area * (h / dist) / d2) : 2 * kPi;
            double cosSurface = dist > 0 ? cosineBound(dot(d, n) / dist, halfDiagonal, dist) : 1;
            // Tiny but never zero where some of it is in front and above.
            return y * std::max(solidAngle * cosSurface, 1e-300);
        }
        case LightType::Environment:
            // A uniform sky of the map's mean radiance gives pi times it on any plane.
            return kPi * luminance(l.environment->averageRadiance());
    }
    return 0;
}

size_t LightSelection::select(const Vec3& p, const Vec3& n, double u, double& probability,
                              std::vector<double>& cdf) const {
    const size_t count = local_.size();
    cdf.resize(count);
    double total = 0;
    for (size_t i = 0; i < count; ++i) {
        total += importanceOf(local_[i], p, n);
        cdf[i] = total;
    }
    if (!(total > 0)) return lights_.size();
    const double target = u * total;
    // The first light whose running sum passes the target; skips lights of importance 0.
    size_t i = static_cast<size_t>(std::upper_bound(cdf.begin(), cdf.end(), target) - cdf.begin());
    if (i >= count) i = count - 1;
    while (i > 0 && cdf[i] == cdf[i - 1]) --i;  // never a zero-importance light at the end
    // Its own importance over the total, exactly as probability() works it out for MIS.
    probability = importanceOf(local_[i], p, n) / total;
    return local_[i].index;
}

double LightSelection::importanceOf(const Local& l, const Vec3& p, const Vec3& n) const {
    return l.rect ? importance(lights_[l.index], p, n)
                  : pointImportance(l.position, l.luminance, p, n);
}

double LightSelection::probability(size_t index, const Vec3& p, const Vec3& n) const {
    if (local_.empty() || !isLocal(lights_[index].type)) return 1;
    double total = 0;
    for (const Local& l : local_) total += importanceOf(l, p, n);
    return total > 0 ? importance(lights_[index], p, n) / total : 0;
}

}  // namespace nenrin
