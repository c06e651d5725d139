#pragma once
/// An AOV-guided denoiser for rendered films: the edge-avoiding à-trous wavelet filter
/// (Dammertz et al., "Edge-Avoiding À-Trous Wavelet Transform for fast Global Illumination
/// Filtering", HPG 2010) steered by the per-pixel variance of the samples as in Schied et al.,
/// "Spatiotemporal Variance-Guided Filtering", HPG 2017 (its spatial part). The radiance's
/// diffuse part (the diffuse AOV) is divided by the albedo AOV before filtering and multiplied
/// by it after, so the wood's grain, which lives in the albedo, is carried by the guide and
/// never blurred; the rest (a coat's gloss, the same over pale and dark wood) is filtered as it
/// is. The filter smooths the illumination, stopping at depth and normal edges, at shadow edges
/// (the visibility AOV), at the darkening into corners (the occlusion AOV) and where luminance
/// differs by far more than the noise explains. Every pixel reads only the previous pass: the
/// result does not depend on the thread count (docs/denoise.md).

#include <string>

#include "renderer/film.h"

namespace nenrin {

struct DenoiseOptions {
    int passes = 3;                ///< à-trous levels: taps 1, 2, 4 apart, reaching 14 pixels
    double sigmaLuminance = 24;    ///< luminance differences in standard deviations of the noise
    double normalExponent = 128;   ///< weight cos(angle between normals)^this
    double sigmaDepth = 1;         ///< depth differences in units of the local depth slope
    double sigmaVisibility = 0.1;  ///< differences in the share of direct light not blocked
    double sigmaOcclusion = 0.1;   ///< differences in how near the first bounce found geometry
    double sigmaAlbedo = 0.07;     ///< albedo (luminance) differences relative to the pixel's
    int threads = 0;               ///< 0 = all cores
    /// Samples per pixel of the film (a render's spp; a film's own `samples` channel wins);
    /// 0 = unknown: the visibility's noise is then not allowed for.
    double samples = 0;
};

/// The filter and its settings in words, for the EXR header (nenrin:denoised).
std::string denoiseDescription(const DenoiseOptions& options);

/// Replaces `film.rgb` and `film.diffuse` by their denoised radiance: the diffuse part
/// divided by the albedo and filtered, the rest (gloss) filtered as it is, each with the same
/// guides but the albedo's. Pixels without a hit (background: alpha 0) are kept and never
/// mixed with hit ones. `film` must hold the whole frame (a split render is
/// denoised after its parts are merged); throws std::invalid_argument otherwise.
void denoiseFilm(Film& film, const DenoiseOptions& options = {});

}  // namespace nenrin
