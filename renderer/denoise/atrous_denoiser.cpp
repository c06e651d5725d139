#include "renderer/denoise/atrous_denoiser.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "grain/rgb.h"
#include "renderer/parallel_tiles.h"

namespace nenrin {

namespace {

double luminance(const float* c) { return luminance(Rgb{c[0], c[1], c[2]}); }

/// What the passes read per pixel: the guides (fixed) and the signal (each pass's output).
struct Guides {
    int width = 0, height = 0;
    std::vector<float> demodulate;  ///< 3 per pixel: the albedo the radiance is divided by
    std::vector<float> normal;      ///< 3 per pixel, unit (0 without a hit)
    std::vector<float> depth, depthSlope;
    std::vector<uint8_t> hit;
};

Guides guidesOf(const Film& film) {
    Guides g;
    g.width = film.width;
    g.height = film.height;
    const size_t n = size_t(film.width) * film.height;
    g.demodulate.assign(3 * n, 1.0f);
    g.normal.assign(3 * n, 0.0f);
    g.depth = film.depth;
    g.depthSlope.assign(n, 0.0f);
    g.hit.assign(n, 0);
    for (size_t i = 0; i < n; ++i) {
        if (!(film.alpha[i] > 0)) continue;
        g.hit[i] = 1;
        // A floor under the albedo keeps black surfaces from dividing by zero.
        for (int c = 0; c < 3; ++c)
            g.demodulate[3 * i + c] = std::max(film.albedo[3 * i + c], 0.01f);
        const float* nrm = &film.normal[3 * i];
        const double len = std::sqrt(double(nrm[0]) * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
        if (len > 0)
            for (int c = 0; c < 3; ++c) g.normal[3 * i + c] = float(nrm[c] / len);
    }
    // The depth's slope (largest of the central differences among hit neighbours): how much
    // depth may change per pixel on one smooth surface.
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
            const size_t i = size_t(y) * g.width + x;
            if (!g.hit[i]) continue;
            float slope = 0;
            auto at = [&](int xx, int yy) {
                xx = std::clamp(xx, 0, g.width - 1);
                yy = std::clamp(yy, 0, g.height - 1);
                const size_t j = size_t(yy) * g.width + xx;
                return g.hit[j] ? g.depth[j] : g.depth[i];
            };
            slope = std::max(std::abs(at(x + 1, y) - at(x - 1, y)),
                             std::abs(at(x, y + 1) - at(x, y - 1))) *
                    0.5f;
            g.depthSlope[i] = std::max(slope, 1e-3f * g.depth[i]);
        }
    return g;
}

/// The variance blurred by a 3 x 3 Gaussian: the luminance weight's noise scale.
std::vector<float> blurredVariance(const std::vector<float>& variance, int w, int h) {
    std::vector<float> out(variance.size());
    constexpr float k[3] = {0.25f, 0.5f, 0.25f};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float s = 0;
            for (int j = -1; j <= 1; ++j)
                for (int i = -1; i <= 1; ++i)
                    s += k[i + 1] * k[j + 1] *
                         variance[size_t(std::clamp(y + j, 0, h - 1)) * w +
                                  std::clamp(x + i, 0, w - 1)];
            out[size_t(y) * w + x] = s;
        }
    return out;
}

/// One à-trous pass at `step`: the illumination and its variance, filtered.
class Pass {
public:
    Pass(const Guides& g, int step, const std::vector<float>& light,
         const std::vector<float>& variance, const DenoiseOptions& o)
        : g_(g),
          step_(step),
          light_(light),
          variance_(variance),
          o_(o),
          noise_(blurredVariance(variance, g.width, g.height)) {}

    /// Pixel (x, y) into the outputs.
    void pixel(int x, int y, std::vector<float>& lightOut, std::vector<float>& varianceOut) const {
        const size_t p = size_t(y) * g_.width + x;
        if (!g_.hit[p]) {  // the sky: kept
            std::copy_n(&light_[3 * p], 3, &lightOut[3 * p]);
            varianceOut[p] = variance_[p];
            return;
        }
        constexpr double kernel[5] = {1.0 / 16, 1.0 / 4, 3.0 / 8, 1.0 / 4, 1.0 / 16};
        const double lp = luminance(&light_[3 * p]);
        const double noise = o_.sigmaLuminance * std::sqrt(std::max(0.0f, noise_[p])) + 1e-10;
        double sum[3] = {0, 0, 0}, weights = 0, varianceSum = 0;
        for (int j = -2; j <= 2; ++j)
            for (int i = -2; i <= 2; ++i) {
                const int qx = x + i * step_, qy = y + j * step_;
                if (qx < 0 || qy < 0 || qx >= g_.width || qy >= g_.height) continue;
                const size_t q = size_t(qy) * g_.width + qx;
                if (!g_.hit[q]) continue;
                double w =
                    kernel[i + 2] * kernel[j + 2] * edgeWeight(p, q, std::abs(i) + std::abs(j));
                if (i != 0 || j != 0)
                    w *= std::exp(-std::abs(lp - luminance(&light_[3 * q])) / noise);
                for (int c = 0; c < 3; ++c) sum[c] += w * light_[3 * q + c];
                weights += w;
                varianceSum += w * w * variance_[q];
            }
        for (int c = 0; c < 3; ++c) lightOut[3 * p + c] = float(sum[c] / weights);
        varianceOut[p] = float(varianceSum / (weights * weights));
    }

private:
    /// How much pixel q lies on p's surface: their normals' agreement and their depths'
    /// difference against p's depth slope over the taps' distance.
    double edgeWeight(size_t p, size_t q, int taps) const {
        const double cosine = g_.normal[3 * p] * g_.normal[3 * q] +
                              g_.normal[3 * p + 1] * g_.normal[3 * q + 1] +
                              g_.normal[3 * p + 2] * g_.normal[3 * q + 2];
        const double normal = std::pow(std::max(0.0, cosine), o_.normalExponent);
        const double depth = std::exp(-std::abs(g_.depth[p] - g_.depth[q]) /
                                      (o_.sigmaDepth * g_.depthSlope[p] * step_ * taps + 1e-9));
        return normal * depth;
    }

    const Guides& g_;
    int step_;
    const std::vector<float>& light_;
    const std::vector<float>& variance_;
    const DenoiseOptions& o_;
    std::vector<float> noise_;  ///< the variance blurred
};

}  // namespace

std::string denoiseDescription(const DenoiseOptions& o) {
    return "edge-avoiding a-trous wavelet, " + std::to_string(o.passes) +
           " passes, guided by albedo, normal, depth and variance (sigma luminance " +
           std::to_string(o.sigmaLuminance) + ", normal exponent " +
           std::to_string(o.normalExponent) + ", sigma depth " + std::to_string(o.sigmaDepth) + ")";
}

void denoiseFilm(Film& film, const DenoiseOptions& options) {
    if (film.firstRow != 0 || film.rows != film.height)
        throw std::invalid_argument("denoise: the film must hold the whole frame");
    if (options.passes < 0 || options.passes > 12)
        throw std::invalid_argument("denoise: 0 to 12 passes");
    const Guides g = guidesOf(film);
    const size_t n = size_t(film.width) * film.height;
    // Demodulated: the illumination, and its variance (the luminance's, over the albedo's
    // luminance squared).
    std::vector<float> light(3 * n), variance(n), lightNext(3 * n), varianceNext(n);
    for (size_t i = 0; i < n; ++i) {
        for (int c = 0; c < 3; ++c)
            light[3 * i + c] = film.rgb[3 * i + c] / g.demodulate[3 * i + c];
        const double a = luminance(&g.demodulate[3 * i]);
        variance[i] = float(film.variance[i] / (a * a));
    }
    for (int k = 0; k < options.passes; ++k) {
        const Pass pass(g, 1 << k, light, variance, options);
        parallelTiles(size_t(g.height), options.threads, [&](size_t y) {
            for (int x = 0; x < g.width; ++x) pass.pixel(x, int(y), lightNext, varianceNext);
        });
        light.swap(lightNext);
        variance.swap(varianceNext);
    }
    for (size_t i = 0; i < n; ++i)
        if (g.hit[i])
            for (int c = 0; c < 3; ++c)
                film.rgb[3 * i + c] = light[3 * i + c] * g.demodulate[3 * i + c];
    for (size_t i = 0; i < n; ++i) {
        const double a = luminance(&g.demodulate[3 * i]);
        film.variance[i] = float(variance[i] * a * a);
    }
}

}  // namespace nenrin
