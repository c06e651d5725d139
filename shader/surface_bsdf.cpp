#include "shader/surface_bsdf.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "shader/ggx.h"

namespace nenrin {

namespace {

constexpr double kInvPi = 1 / std::numbers::pi;

Rgb schlickRgb(double cosTheta, const Rgb& f0) {
    return {ggx::schlick(cosTheta, f0.r), ggx::schlick(cosTheta, f0.g),
            ggx::schlick(cosTheta, f0.b)};
}

/// Refracts a direction above a flat interface into the medium below (index ior), keeping it
/// pointing away from the surface: the angle fibres see light and viewer at.
Vec3 refractInto(const Vec3& w, double ior) {
    double sin2 = std::max(0.0, 1 - w.z * w.z) / (ior * ior);
    return {w.x / ior, w.y / ior, std::sqrt(std::max(0.0, 1 - sin2))};
}

Vec3 cosineHemisphere(double u1, double u2) {
    double r = std::sqrt(u1), phi = 2 * std::numbers::pi * u2;
    return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1 - u1))};
}

}  // namespace

double SurfaceBsdf::coatProbability(const Vec3& wo) const {
    if (coatWeight <= 0) return 0;
    double f = coatWeight * ggx::schlick(wo.z, ggx::dielectricF0(ior));
    return std::clamp(0.1 + 2 * f, 0.1, 0.75);
}

Rgb SurfaceBsdf::fibreLobe(const Vec3& wo, const Vec3& wi) const {
    if (fibreStrength <= 0 || lengthSquared(fibre) == 0) return {};
    // Inclinations from the plane normal to the fibre, inside the wood. A fibre reflects
    // light into a cone: psi_r = -psi_i, so the lobe is centred on psi_h = 0.
    Vec3 i = refractInto(wi, ior), o = refractInto(wo, ior);
    double psiI = std::asin(std::clamp(dot(i, fibre), -1.0, 1.0));
    double psiR = std::asin(std::clamp(dot(o, fibre), -1.0, 1.0));
    double psiH = 0.5 * (psiI + psiR);
    double cosHalfD = std::cos(0.5 * (psiR - psiI));
    double beta = fibreWidth;
    double g =
        std::exp(-0.5 * psiH * psiH / (beta * beta)) / (beta * std::sqrt(2 * std::numbers::pi));
    // 1 / (2 pi) makes the lobe's hemispherical reflectance about fibreStrength / 2 (the cone
    // covers roughly half of the sphere's half-angle range above the surface).
    double k = fibreStrength * g / (cosHalfD * cosHalfD) * (0.5 * kInvPi);
    return base * k;
}

Rgb SurfaceBsdf::evaluate(const Vec3& wo, const Vec3& wi, Rgb& diffuse) const {
    diffuse = {};
    if (wo.z <= 0 || wi.z <= 0) return {};
    Vec3 h = normalize(wo + wi);
    if (metal) {
        double d = ggx::distribution(h, metalAlpha);
        double g = ggx::smithG1(wo, metalAlpha) * ggx::smithG1(wi, metalAlpha);
        return schlickRgb(dot(wo, h), metalF0) * (d * g / (4 * wo.z * wi.z));
    }
    Rgb under = base * kInvPi + fibreLobe(wo, wi);
    if (coatWeight <= 0) {
        diffuse = under;
        return under;
    }
    double f0 = ggx::dielectricF0(ior);
    double d = ggx::distribution(h, coatAlpha);
    double g = ggx::smithG1(wo, coatAlpha) * ggx::smithG1(wi, coatAlpha);
    double coat = coatWeight * ggx::schlick(dot(wo, h), f0) * d * g / (4 * wo.z * wi.z);
    double through =
        (1 - coatWeight * ggx::schlick(wi.z, f0)) * (1 - coatWeight * ggx::schlick(wo.z, f0));
    diffuse = under * through;
    return diffuse + Rgb{coat, coat, coat};
}

double SurfaceBsdf::pdf(const Vec3& wo, const Vec3& wi) const {
    if (wo.z <= 0 || wi.z <= 0) return 0;
    Vec3 h = normalize(wo + wi);
    if (metal) return ggx::reflectionPdf(wo, h, metalAlpha);
    double pc = coatProbability(wo);
    double p = (1 - pc) * wi.z * kInvPi;
    if (pc > 0) p += pc * ggx::reflectionPdf(wo, h, coatAlpha);
    return p;
}

bool SurfaceBsdf::sample(const Vec3& wo, double uLobe, double u1, double u2, Sample& out) const {
    if (wo.z <= 0) return false;
    Vec3 wi;
    if (metal) {
        wi = ggx::reflect(wo, ggx::sampleVisibleNormal(wo, metalAlpha, u1, u2));
        out.roughness = metalAlpha;
    } else if (uLobe < coatProbability(wo)) {
        wi = ggx::reflect(wo, ggx::sampleVisibleNormal(wo, coatAlpha, u1, u2));
        out.roughness = coatAlpha;
    } else {
        wi = cosineHemisphere(u1, u2);
        out.roughness = 1;
    }
    if (wi.z <= 0) return false;
    out.wi = wi;
    out.pdf = pdf(wo, wi);
    if (!(out.pdf > 0)) return false;
    out.weight = evaluate(wo, wi, out.diffuseWeight) * (wi.z / out.pdf);
    out.diffuseWeight = out.diffuseWeight * (wi.z / out.pdf);
    return true;
}

}  // namespace nenrin
