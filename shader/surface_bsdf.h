#pragma once
/// One layered surface model for every material nenrin renders, in a local shading frame
/// (normal +z; directions point away from the surface):
///  - a Lambert base (albedo / pi),
///  - a fibre highlight under the coat after Marschner, Westin, Lu and Lu 2005, "Measuring and
///    modeling the appearance of finished wood": a Gaussian lobe in the half angle psi_h about
///    the fibre axis, with both directions refracted into the wood first,
///  - a clear GGX coat on top (Schlick Fresnel) that takes its reflected share from the light
///    reaching the layers below, or instead
///  - a GGX conductor (metal) with a coloured Schlick Fresnel.
/// Wood sets every layer; "diffuse" only the base; "glossy" base + coat; "metal" the conductor.

#include "grain/rgb.h"
#include "util/vec3.h"

namespace nenrin {

struct SurfaceBsdf {
    Rgb base;               ///< Lambert albedo
    double coatWeight = 0;  ///< 0..1
    double coatAlpha = 0.1;
    double ior = 1.5;  ///< coat film and wood fibres
    Vec3 fibre;        ///< unit fibre direction in the local frame; zero = no fibre lobe
    double fibreStrength = 0;
    double fibreWidth = 0.14;  ///< radians
    bool metal = false;
    Rgb metalF0;  ///< reflectance of the metal at normal incidence
    double metalAlpha = 0.2;

    /// f(wo, wi) without the cosine; zero unless both directions are above the surface.
    Rgb evaluate(const Vec3& wo, const Vec3& wi) const {
        Rgb diffuse;
        return evaluate(wo, wi, diffuse);
    }
    /// The same, and into `diffuse` the part of it the albedo carries: the base and the fibre
    /// lobe under the coat (the rest is the coat's or the metal's reflection, the same over
    /// pale and dark wood). The denoiser divides only this part by the albedo.
    Rgb evaluate(const Vec3& wo, const Vec3& wi, Rgb& diffuse) const;
    /// Solid-angle density with which sample() picks wi.
    double pdf(const Vec3& wo, const Vec3& wi) const;

    struct Sample {
        Vec3 wi;
        Rgb weight;         ///< f cos(theta_i) / pdf
        Rgb diffuseWeight;  ///< the same of f's diffuse part (evaluate)
        double pdf = 0;
        double roughness = 1;  ///< GGX alpha of the lobe it came from, 1 for the diffuse base
    };
    /// Picks wi from three uniform numbers; false if none (wo below the surface, or a sample
    /// below the horizon).
    bool sample(const Vec3& wo, double uLobe, double u1, double u2, Sample& out) const;

private:
    double coatProbability(const Vec3& wo) const;
    Rgb fibreLobe(const Vec3& wo, const Vec3& wi) const;
};

}  // namespace nenrin
