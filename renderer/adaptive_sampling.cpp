#include "renderer/adaptive_sampling.h"

#include <algorithm>
#include <limits>

namespace nenrin {

namespace {

/// Samples every pixel takes before its noise is first estimated, unless the scene says.
constexpr uint32_t kDefaultMinSpp = 16;

}  // namespace

void TileSampling::start(int tw, int th, const RenderSettings& settings) {
    tw_ = tw;
    th_ = th;
    spp_ = static_cast<uint32_t>(settings.spp);
    threshold_ = settings.noiseThreshold;
    const size_t pixels = size_t(tw) * th;
    adaptive_ = threshold_ > 0;
    const uint32_t firstRound =
        adaptive_ ? std::min(spp_, settings.minSpp > 0 ? static_cast<uint32_t>(settings.minSpp)
                                                       : std::min(spp_, kDefaultMinSpp))
                  : spp_;
    done_.assign(pixels, 0);
    target_.assign(pixels, firstRound);
    rgbHalf_.assign(adaptive_ ? pixels : 0, Rgb{});
    halfCount_.assign(adaptive_ ? pixels : 0, firstRound / 2);
}

uint32_t TileSampling::longestRound() const {
    uint32_t longest = 0;
    for (size_t p = 0; p < done_.size(); ++p) longest = std::max(longest, target_[p] - done_[p]);
    return longest;
}

void TileSampling::endRound(const std::vector<Rgb>& rgb) {
    done_ = target_;
    if (!adaptive_) return;
    planNextRound(rgb);
    // The next estimate compares a pixel's mean with the mean of the samples it has now.
    for (size_t p = 0; p < done_.size(); ++p)
        if (target_[p] > done_[p]) {
            rgbHalf_[p] = rgb[p];
            halfCount_[p] = done_[p];
        }
}

void TileSampling::planNextRound(const std::vector<Rgb>& rgb) {
    // Each pixel's noise: how far its mean I over n samples has moved from the mean A of its
    // first m (half of them): for independent samples E|I - A|^2 = sigma^2 (1/m - 1/n), so
    // |I - A|^2 m / (n - m) estimates the squared standard error of I, and with stratified
    // samples it follows their faster convergence. Summed over R, G, B and taken over the mean
    // (the error after a display's gamma, up to a factor). One such draw is noisy, so each
    // pixel takes the mean of its 3 x 3 neighbourhood's (27 draws) before it is compared.
    const int tw = tw_, th = th_;
    const size_t pixels = size_t(tw) * th;
    std::vector<double>& ratio = noiseRatio_;
    ratio.assign(pixels, 0);
    for (size_t p = 0; p < pixels; ++p) {
        const double n = done_[p], m = halfCount_[p];
        if (m < 1 || n <= m) {
            ratio[p] = std::numeric_limits<double>::infinity();
            continue;
        }
        const Rgb mean = rgb[p] * (1 / n);
        const Rgb d = mean - rgbHalf_[p] * (1 / m);
        const double error2 = (d.r * d.r + d.g * d.g + d.b * d.b) * m / (n - m);
        ratio[p] = error2 / std::max(mean.r + mean.g + mean.b, 1e-4);
    }
    std::vector<uint8_t>& noisy = noisy_;
    noisy.assign(pixels, 0);
    for (int j = 0; j < th; ++j)
        for (int i = 0; i < tw; ++i) {
            double sum = 0;
            int count = 0;
            for (int v = std::max(0, j - 1); v <= std::min(th - 1, j + 1); ++v)
                for (int u = std::max(0, i - 1); u <= std::min(tw - 1, i + 1); ++u, ++count)
                    sum += ratio[size_t(v) * tw + u];
            noisy[size_t(j) * tw + i] = sum > threshold_ * threshold_ * count;
        }
    // A pixel goes on if it or a neighbour is noisy: a single estimate from few samples can
    // look converged by chance, and noise comes in patches.
    for (int j = 0; j < th; ++j)
        for (int i = 0; i < tw; ++i) {
            const size_t p = size_t(j) * tw + i;
            bool more = false;
            for (int dj = -1; dj <= 1 && !more; ++dj)
                for (int di = -1; di <= 1 && !more; ++di) {
                    const int u = i + di, v = j + dj;
                    more = u >= 0 && v >= 0 && u < tw && v < th && noisy[size_t(v) * tw + u];
                }
            if (more) target_[p] = std::min(spp_, 2 * done_[p]);
        }
}

}  // namespace nenrin
