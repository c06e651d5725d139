#pragma once
/// How many samples each pixel of a tile takes (docs/render.md#adaptive-sampling). Without a
/// noise threshold, spp each, in one round. With one, in rounds: every pixel first takes
/// minSpp samples; then each pixel whose pooled noise estimate, or a neighbour's, is above the
/// threshold doubles its samples, up to spp. Decisions use the tile's pixels only (tiles are
/// fixed, whatever the thread count), and a pixel's k-th sample is the same whichever round
/// takes it: the image is deterministic.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "grain/rgb.h"
#include "renderer/scene.h"

namespace nenrin {

class TileSampling {
public:
    /// Starts a tile of tw x th pixels: each pixel's target is the first round's samples.
    void start(int tw, int th, const RenderSettings& settings);

    /// Per pixel (row-major in the tile): samples taken in the rounds before this one, and
    /// samples the pixel will have taken at the end of this one.
    const std::vector<uint32_t>& samplesDone() const { return done_; }
    const std::vector<uint32_t>& samplesTarget() const { return target_; }

    /// The most samples a pixel takes in this round; 0 once the tile is finished.
    uint32_t longestRound() const;

    /// A finished sample of `pixel`, whose radiance has been added to the pixel's sum: the noise
    /// estimate also needs the sum over the pixel's first samples.
    void addSample(uint32_t pixel, uint32_t sample, const Rgb& radiance) {
        if (!halfCount_.empty() && sample < halfCount_[pixel])
            rgbHalf_[pixel] = rgbHalf_[pixel] + radiance;
    }

    /// Ends a round: its samples are done. With a noise threshold, the pixels that are still
    /// noisy (from `rgb`, the sum of each pixel's samples) get a next round.
    void endRound(const std::vector<Rgb>& rgb);

private:
    /// Raises target_ of the pixels that need more samples.
    void planNextRound(const std::vector<Rgb>& rgb);

    int tw_ = 0, th_ = 0;
    uint32_t spp_ = 0;
    bool adaptive_ = false;  ///< a noise threshold: rounds
    double threshold_ = 0;
    std::vector<uint32_t> done_, target_;
    /// The radiance of the pixel's first halfCount_ samples (with a threshold only).
    std::vector<Rgb> rgbHalf_;
    std::vector<uint32_t> halfCount_;
    std::vector<double> noiseRatio_;  ///< planNextRound's scratch
    std::vector<uint8_t> noisy_;      ///< planNextRound's scratch
};

}  // namespace nenrin
