#pragma once
/// GGX (Trowbridge-Reitz) microfacet terms in a local frame with the normal along +z, and
/// sampling of the visible normals (Heitz 2018), shared by the coat of the wood and the glossy
/// and metal materials. Directions point away from the surface.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "util/vec3.h"

namespace nenrin::ggx {

inline double distribution(const Vec3& h, double alpha) {
    if (h.z <= 0) return 0;
    double a2 = alpha * alpha;
    double c2 = h.z * h.z;
    double d = c2 * (a2 - 1) + 1;
    return a2 / (std::numbers::pi * d * d);
}

/// Smith's masking for one direction.
inline double smithG1(const Vec3& w, double alpha) {
    if (w.z <= 0) return 0;
    double c2 = w.z * w.z;
    double t2 = std::max(0.0, 1 - c2) / c2;
    return 2 / (1 + std::sqrt(1 + alpha * alpha * t2));
}

/// Schlick's Fresnel for a dielectric of reflectance f0 at normal incidence.
inline double schlick(double cosTheta, double f0) {
    double m = std::clamp(1 - cosTheta, 0.0, 1.0);
    double m2 = m * m;
    return f0 + (1 - f0) * m2 * m2 * m;
}

inline double dielectricF0(double ior) {
    double r = (ior - 1) / (ior + 1);
    return r * r;
}

/// A visible normal for direction wo (wo.z > 0) from two uniform numbers.
inline Vec3 sampleVisibleNormal(const Vec3& wo, double alpha, double u1, double u2) {
    Vec3 vh = normalize(Vec3{alpha * wo.x, alpha * wo.y, wo.z});
    double lensq = vh.x * vh.x + vh.y * vh.y;
    Vec3 t1 = lensq > 0 ? Vec3{-vh.y, vh.x, 0} / std::sqrt(lensq) : Vec3{1, 0, 0};
    Vec3 t2 = cross(vh, t1);
    double r = std::sqrt(u1);
    double phi = 2 * std::numbers::pi * u2;
    double p1 = r * std::cos(phi), p2 = r * std::sin(phi);
    double s = 0.5 * (1 + vh.z);
    p2 = (1 - s) * std::sqrt(std::max(0.0, 1 - p1 * p1)) + s * p2;
    Vec3 nh = t1 * p1 + t2 * p2 + vh * std::sqrt(std::max(0.0, 1 - p1 * p1 - p2 * p2));
    return normalize(Vec3{alpha * nh.x, alpha * nh.y, std::max(1e-7, nh.z)});
}

/// Density (solid angle of wi) of reflecting wo about a sampled visible normal h.
inline double reflectionPdf(const Vec3& wo, const Vec3& h, double alpha) {
    double woh = dot(wo, h);
    if (wo.z <= 0 || woh <= 0) return 0;
    return smithG1(wo, alpha) * distribution(h, alpha) / (4 * wo.z);
}

inline Vec3 reflect(const Vec3& w, const Vec3& h) { return h * (2 * dot(w, h)) - w; }

}  // namespace nenrin::ggx
