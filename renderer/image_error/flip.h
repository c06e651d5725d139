#pragma once
/// FLIP, the perceptual image difference renderer test suites use (Andersson et al., "FLIP: A
/// Difference Evaluator for Alternating Images", HPG 2020), and its HDR extension (Andersson
/// et al., "Visualizing Errors in Rendered High Dynamic Range Images", Eurographics 2021):
/// a per-pixel error in [0, 1] for a viewer at a given number of pixels per degree of visual
/// angle. LDR-FLIP filters both images by the eye's contrast sensitivity in an opponent colour
/// space, measures the Hunt-adjusted HyAB colour distance, and raises it where edges and points
/// differ. HDR-FLIP tone-maps both images (ACES filmic) at exposures from the reference's
/// brightest pixel down to its median and keeps each pixel's largest LDR-FLIP.

#include <vector>

namespace nenrin {

/// Pixels per degree of a viewer 0.7 m from a 0.7 m wide monitor of 3840 pixels (FLIP's
/// default observer): 3840 * pi / 180.
inline constexpr double kFlipDefaultPpd = 67.02064327658226;

/// An RGB image: 3 floats per pixel, row 0 at the top.
struct FlipImage {
    int width = 0, height = 0;
    std::vector<float> rgb;
};

/// LDR-FLIP of two images of sRGB-encoded values (clamped to [0, 1]) of one size: the error
/// per pixel, row-major.
std::vector<float> ldrFlip(const FlipImage& reference, const FlipImage& test,
                           double ppd = kFlipDefaultPpd);

/// HDR-FLIP's exposures (stops relative to the images' values): `count` from `start` to `stop`.
struct FlipExposures {
    double start = 0, stop = 0;
    int count = 2;
};

/// The exposures the HDR extension derives from the reference (linear, scene-referred):
/// the brightest pixel's luminance mapped to 0.85 at the start, the median's at the stop,
/// max(2, ceil(stop - start)) of them. A black reference gives 0, 0.
FlipExposures flipExposures(const FlipImage& reference);

/// HDR-FLIP of two linear images: the largest LDR-FLIP per pixel over the exposures, each
/// image tone-mapped by the ACES filmic curve and encoded as sRGB. Negative values count as 0.
std::vector<float> hdrFlip(const FlipImage& reference, const FlipImage& test,
                           const FlipExposures& exposures, double ppd = kFlipDefaultPpd);

}  // namespace nenrin
