#include "renderer/texture_set/pbr_finish.h"

#include <algorithm>
#include <cmath>

namespace nenrin {

namespace {

/// Marschner's fibre highlight is narrow along the fibre (its Gaussian width) and spread all
/// round it: across the fibres the stretched lobe reaches alpha = mix(alpha, 1, 0.9²) ~ 0.84.
constexpr double kFibreAnisotropy = 0.9;

}  // namespace

double perceptualRoughness(double ggxAlpha) { return std::sqrt(std::clamp(ggxAlpha, 0.0, 1.0)); }

PbrFinish pbrFinish(const Finish& finish) {
    PbrFinish p;
    p.coatWeight = std::clamp(finish.coatWeight, 0.0, 1.0);
    p.coatRoughness = perceptualRoughness(finish.coatRoughness);
    p.ior = finish.coatIor;
    p.fibreStrength = finish.fibreStrength;
    if (finish.fibreStrength > 0) {
        // The Gaussian width (radians) stands for the GGX alpha along the fibre: both are the
        // slope spread of the lobe for small angles.
        p.baseRoughness = perceptualRoughness(finish.fibreWidth);
        p.anisotropy = kFibreAnisotropy;
    } else {
        p.baseRoughness = perceptualRoughness(finish.woodRoughness);
        p.anisotropy = 0;
    }
    return p;
}

}  // namespace nenrin
