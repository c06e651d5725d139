#pragma once
/// How nenrin's layered wood surface (shader/surface_bsdf.h: a Lambert base, the fibre highlight
/// under a clear GGX coat) maps onto the layered PBR model of other tools: glTF 2.0 with
/// KHR_materials_clearcoat and KHR_materials_anisotropy, Blender's Principled BSDF, the PBR
/// extension of MTL. The coat becomes the clear coat; the fibre highlight becomes the base's
/// specular lobe, stretched across the fibres. Roughness is perceptual (GGX alpha = r²), what
/// those tools expect. The table per tool is in docs/uv-bake.md.

#include "shader/finish.h"

namespace nenrin {

struct PbrFinish {
    double coatWeight = 0;     ///< clear coat factor, 0..1
    double coatRoughness = 0;  ///< perceptual roughness of the coat
    double ior = 1.5;          ///< of the coat (and the base's dielectric specular)
    /// Perceptual roughness of the base's specular lobe: along the fibres it is the width of
    /// nenrin's fibre highlight; for a finish without one (bare) the wood's own roughness.
    double baseRoughness = 0.5;
    /// glTF anisotropyStrength (0..1): how far the base lobe is stretched across the fibres
    /// (alpha across = mix(alpha, 1, strength²)); 0 without a fibre highlight.
    double anisotropy = 0;
    /// nenrin's fibre highlight strength (albedo-tinted), for hosts that can tint a lobe.
    double fibreStrength = 0;
};

/// Perceptual roughness from a GGX alpha (r = sqrt(alpha)), for alpha in [0, 1].
double perceptualRoughness(double ggxAlpha);

PbrFinish pbrFinish(const Finish& finish);

}  // namespace nenrin
