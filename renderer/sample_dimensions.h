#pragma once
/// The random numbers of the path tracer, by name. Every random number is a pure function of
/// (seed, pixel, sample, dimension), so the image does not depend on thread count or tile order,
/// and a pixel's k-th sample is the same whichever round of adaptive sampling takes it. This
/// file is the one map of the dimensions: two draws that shared one would be correlated. The
/// (seed, pixel) part is hashed once per pixel, into the pixel's key.
///
///   dimension                  draw     what
///   0, 1 of kPixelSample       random   rotation of the pixel's jitter sequence (per pixel)
///   2                          pair     the lens point (thin-lens cameras only)
///   bounceBase(depth) + ...             one bounce (depth 0: the camera hit), spaced apart
///     kBsdfLobe                random   which lobe of the BSDF to sample
///     kBsdfDirection           pair     the direction within the lobe
///     kRoulette                random   Russian roulette
///     lightPair(k)             pair     the point on the k-th light sampled here
///     lightPick(n)             random   which local light to pick (after n every-vertex lights)

#include <cstddef>
#include <cstdint>
#include <utility>

#include "util/hash.h"
#include "util/scrambled_sobol.h"

namespace nenrin {

/// The key of one pixel's random numbers: the seed and the pixel, hashed.
inline uint64_t pixelKey(uint64_t seed, uint64_t pixel) { return hashCombine(seed, pixel); }

/// The counter-based random number for (pixel, sample, dimension).
inline double randomAt(uint64_t pixelKey, uint64_t sample, uint64_t dimension) {
    return uniform01(pixelKey, sample, dimension);
}

/// Two dimensions that sample one 2D domain together (a lens point, a light point, a BSDF
/// direction): a scrambled Sobol pair of their own per pixel, so a pixel's samples stratify
/// each such domain.
inline std::pair<double, double> pairAt(uint64_t pixelKey, uint64_t sample, uint64_t dimension) {
    return scrambledSobol2D(static_cast<uint32_t>(sample), hashCombine(pixelKey, dimension));
}

namespace dimension {

/// Not a sample the pixel takes: the per-pixel draws (the jitter rotation) use this index.
inline constexpr uint64_t kPixelSample = 0xffffffffull;
/// The per-pixel rotation of the R2 sequence that jitters the samples within the pixel.
inline constexpr uint64_t kJitterRotationX = 0;
inline constexpr uint64_t kJitterRotationY = 1;
/// The sample's point on the lens (a pair: dimensions 2 and 3).
inline constexpr uint64_t kLens = 2;

/// Where the first bounce's dimensions start: after the camera's.
inline constexpr uint64_t kFirstBounce = 4;
/// Bounces are spaced far apart so a scene's light count never makes two bounces share one.
inline constexpr uint64_t kPerBounce = 1 << 16;

// Offsets from a bounce's base.
inline constexpr uint64_t kBsdfLobe = 0;
/// A pair: dimensions 1 and 2.
inline constexpr uint64_t kBsdfDirection = 1;
inline constexpr uint64_t kRoulette = 3;
/// Light samples, a pair each, from here on.
inline constexpr uint64_t kFirstLight = 4;
inline constexpr uint64_t kPerLight = 2;

/// The first dimension of bounce `depth` (0: at the camera hit).
constexpr uint64_t bounceBase(int depth) { return kFirstBounce + depth * kPerBounce; }
/// The pair of the k-th light a vertex samples.
constexpr uint64_t lightPair(size_t k) { return kFirstLight + kPerLight * k; }
/// The pick of one local light, at a vertex that samples `everyVertex` lights besides it: the
/// dimension after the picked light's pair.
constexpr uint64_t lightPick(size_t everyVertex) { return lightPair(everyVertex + 1); }

}  // namespace dimension

/// The random numbers of one bounce of one path sample, by offset from the bounce's base.
class BounceRandom {
public:
    BounceRandom(uint64_t pixelKey, uint64_t sample, int depth)
        : pixelKey_(pixelKey), sample_(sample), base_(dimension::bounceBase(depth)) {}

    double at(uint64_t offset) const { return randomAt(pixelKey_, sample_, base_ + offset); }
    std::pair<double, double> pair(uint64_t offset) const {
        return pairAt(pixelKey_, sample_, base_ + offset);
    }

private:
    uint64_t pixelKey_, sample_, base_;
};

}  // namespace nenrin
