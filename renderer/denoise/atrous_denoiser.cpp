#include "renderer/denoise/atrous_denoiser.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "grain/rgb.h"
#include "renderer/parallel_tiles.h"

namespace nenrin {

namespace {

double luminance(const float* c) { return luminance(Rgb{c[0], c[1], c[2]}); }

/// Visibility (and occlusion) differences up to this many of its estimate's standard
/// deviations are its noise (showroom-downlights at 32 spp: FLIP 0.0387 -> 0.0374 and RMSE
/// 0.0152 -> 0.0133 with 2 against none; 3 and 5 smooth the showroom a little more and blur
/// table-top-room's penumbrae).
constexpr double kVisibilityNoise = 2;

/// A guide's scale `sigma` widened by the noise of its value `share`, a share of `samples`
/// samples: as noisy as a coin's tosses, share (1 - share) / samples. With many lights (one
/// picked per sample) the visibility is that noisy, and a noisy guide would stop the filter
/// everywhere; 0 or 1 (a clean shadow edge) keeps sigma as it is. samples 0: unknown, sigma.
double withShareNoise(double sigma, double share, double samples) {
    if (!(samples > 0)) return sigma;
    const double v = std::clamp(share, 0.0, 1.0);
    const double noise = kVisibilityNoise * std::sqrt(v * (1 - v) / samples);
    return std::sqrt(sigma * sigma + noise * noise);
}

/// What the passes read per pixel: the guides (fixed) and the signal (each pass's output).
struct Guides {
    int width = 0, height = 0;
    std::vector<float> demodulate;  ///< 3 per pixel: the albedo the radiance is divided by
    std::vector<float> normal;      ///< 3 per pixel, unit (0 without a hit)
    std::vector<float> depth, depthSlope;
    std::vector<float> depthGradient;    ///< 2 per pixel: dz/dx, dz/dy (the smoother side's)
    std::vector<float> visibility;       ///< the first hit's unblocked share of its direct light
    std::vector<float> visibilityScale;  ///< sigma visibility, widened by its estimate's noise
    std::vector<float> albedo;           ///< the luminance of `demodulate`
    std::vector<float> occlusion;        ///< how close the first bounce found geometry
    std::vector<float> occlusionScale;   ///< sigma occlusion, widened by its estimate's noise
    std::vector<uint8_t> hit;
};

Guides guidesOf(const Film& film, const DenoiseOptions& o) {
    Guides g;
    g.width = film.width;
    g.height = film.height;
    const size_t n = size_t(film.width) * film.height;
    g.demodulate.assign(3 * n, 1.0f);
    g.normal.assign(3 * n, 0.0f);
    g.depth.assign(film.depth.begin(), film.depth.end());
    g.visibility.assign(film.visibility.begin(), film.visibility.end());
    g.visibilityScale.assign(n, float(o.sigmaVisibility));
    g.albedo.assign(n, 1.0f);
    g.depthSlope.assign(n, 0.0f);
    g.depthGradient.assign(2 * n, 0.0f);
    g.hit.assign(n, 0);
    g.occlusion.assign(film.occlusion.begin(), film.occlusion.end());
    g.occlusionScale.assign(n, float(o.sigmaOcclusion));
    for (size_t i = 0; i < n; ++i) {
        if (!(film.alpha[i] > 0)) continue;
        g.hit[i] = 1;
        // A floor under the albedo keeps black surfaces from dividing by zero.
        for (int c = 0; c < 3; ++c)
            g.demodulate[3 * i + c] = std::max(film.albedo[3 * i + c], 0.01f);
        g.albedo[i] = float(luminance(&g.demodulate[3 * i]));
        // Visibility is a share of the samples; occlusion a mean of values in [0, 1], no
        // noisier than such a share.
        const double samples = film.samples.empty() ? o.samples : film.samples[i];
        g.visibilityScale[i] =
            float(withShareNoise(o.sigmaVisibility, film.visibility[i], samples));
        g.occlusionScale[i] = float(withShareNoise(o.sigmaOcclusion, film.occlusion[i], samples));
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
            // Of the differences to either side, the smaller: across a silhouette one side
            // jumps, the other continues the surface.
            auto smoother = [](float ahead, float behind) {
                return std::abs(ahead) < std::abs(behind) ? ahead : behind;
            };
            g.depthGradient[2 * i] = smoother(at(x + 1, y) - g.depth[i], g.depth[i] - at(x - 1, y));
            g.depthGradient[2 * i + 1] =
                smoother(at(x, y + 1) - g.depth[i], g.depth[i] - at(x, y - 1));
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

/// k where exponent = 2^k (0 to 10), else -1: cos^exponent is then k squarings, no log.
int powerOfTwoSquarings(double exponent) {
    for (int k = 0; k <= 10; ++k)
        if (exponent == double(1 << k)) return k;
    return -1;
}

/// One à-trous pass at `step`: the illumination and its variance, filtered.
class Pass {
public:
    Pass(const Guides& g, int step, const std::vector<float>& light,
         const std::vector<float>& variance, const DenoiseOptions& o, bool gloss)
        : g_(g),
          step_(step),
          glossPass_(gloss),
          light_(light),
          variance_(variance),
          o_(o),
          noise_(blurredVariance(variance, g.width, g.height)),
          luma_(light.size() / 3),
          squarings_(powerOfTwoSquarings(o.normalExponent)) {
        for (size_t i = 0; i < luma_.size(); ++i) luma_[i] = luminance(&light[3 * i]);
    }

    /// Pixel (x, y) into the outputs.
    void pixel(int x, int y, std::vector<float>& lightOut, std::vector<float>& varianceOut) const {
        const size_t p = size_t(y) * g_.width + x;
        // The sky is kept; so is a gloss of exactly 0 (a matte surface's: nothing to filter).
        const bool none =
            glossPass_ && light_[3 * p] == 0 && light_[3 * p + 1] == 0 && light_[3 * p + 2] == 0;
        if (!g_.hit[p] || none) {
            std::copy_n(&light_[3 * p], 3, &lightOut[3 * p]);
            varianceOut[p] = variance_[p];
            return;
        }
        constexpr double kernel[5] = {1.0 / 16, 1.0 / 4, 3.0 / 8, 1.0 / 4, 1.0 / 16};
        const Centre centre = centreOf(p);
        double sum[3] = {0, 0, 0}, weights = 0, varianceSum = 0;
        for (int j = -2; j <= 2; ++j)
            for (int i = -2; i <= 2; ++i) {
                const int qx = x + i * step_, qy = y + j * step_;
                if (qx < 0 || qy < 0 || qx >= g_.width || qy >= g_.height) continue;
                const size_t q = size_t(qy) * g_.width + qx;
                if (!g_.hit[q]) continue;
                double normal = 1;
                const double distance = edgeDistance(centre, q, i, j, normal);
                // Past e^-40 a weight is nothing beside the centre's: one exp saved.
                if (!(distance < 40)) continue;
                // A float exp: the weights need no more than its 1e-7, and it is twice as fast.
                const double w =
                    kernel[i + 2] * kernel[j + 2] * normal * double(std::exp(-float(distance)));
                for (int c = 0; c < 3; ++c) sum[c] += w * light_[3 * q + c];
                weights += w;
                varianceSum += w * w * variance_[q];
            }
        for (int c = 0; c < 3; ++c) lightOut[3 * p + c] = float(sum[c] / weights);
        varianceOut[p] = float(varianceSum / (weights * weights));
    }

private:
    /// Pixel p's guides, and the reciprocals of its scales (a multiply per tap, not a divide).
    struct Centre {
        size_t index;
        double normal[3], depth, depthGradient[2], visibility, occlusion, albedo, luminance;
        double perDepth, perVisibility, perOcclusion, perAlbedo, perLuminance;
    };

    Centre centreOf(size_t p) const {
        Centre c;
        c.index = p;
        for (int k = 0; k < 3; ++k) c.normal[k] = g_.normal[3 * p + k];
        c.depth = g_.depth[p];
        c.depthGradient[0] = g_.depthGradient[2 * p];
        c.depthGradient[1] = g_.depthGradient[2 * p + 1];
        c.visibility = g_.visibility[p];
        c.occlusion = g_.occlusion[p];
        c.albedo = g_.albedo[p];
        c.luminance = luma_[p];
        c.perDepth = 1 / (o_.sigmaDepth * g_.depthSlope[p] * step_ + 1e-9);
        c.perVisibility = 1 / double(g_.visibilityScale[p]);
        c.perOcclusion = 1 / double(g_.occlusionScale[p]);
        // The gloss has no albedo guide.
        c.perAlbedo = glossPass_ ? 0.0 : 1 / (o_.sigmaAlbedo * g_.albedo[p]);
        c.perLuminance = 1 / (o_.sigmaLuminance * std::sqrt(std::max(0.0f, noise_[p])) + 1e-10);
        return c;
    }

    /// How much pixel q lies on p's surface, lit as p is: their normals' agreement, q's depth
    /// off p's plane (its depth and depth gradient) against p's depth slope over the taps'
    /// distance, their shares of direct light not blocked (a shadow's edge, which no other
    /// guide shows), their occlusions (how near the first bounce found geometry: the darkening
    /// of indirect light into a corner or at a leg's foot, which a filter reaching past it
    /// would brighten), and, for the diffuse part, their albedos' relative difference: its
    /// light over the albedo is not only the light where the wood's fibre lobe (a sheen along
    /// the fibres) or, in a render without the diffuse AOV, a coat's gloss adds to it (the same
    /// gloss over dark and pale boards steps the quotient at every board, knot and ring), and
    /// filtering across would smear those steps; last, their luminances' difference against
    /// p's noise. The weights multiply, so their logarithms add: returned is minus the log of
    /// exp(-depth term) x exp(-visibility term) x ... , one exp for the lot, and
    /// `normalWeight` is set to cos^exponent (by squarings where the exponent is a power of
    /// two, as the default 128 is: no log; else its log is in the sum and the weight left 1).
    /// Infinite where the normals are 90 degrees or more apart; 0 for p itself, whose weight
    /// keeps the sum above zero even without a normal. (i, j): q's taps from p.
    double edgeDistance(const Centre& p, size_t q, int i, int j, double& normalWeight) const {
        if (p.index == q) return 0;
        const double cosine = p.normal[0] * g_.normal[3 * q] + p.normal[1] * g_.normal[3 * q + 1] +
                              p.normal[2] * g_.normal[3 * q + 2];
        if (!(cosine > 0)) return HUGE_VAL;
        double normal = 0;
        if (cosine < 1) {
            if (squarings_ >= 0) {
                normalWeight = cosine;
                for (int k = 0; k < squarings_; ++k) normalWeight *= normalWeight;
            } else {
                normal = -o_.normalExponent * std::log(cosine);
            }
        }
        // q's depth against p's plane: a slanted wall is no edge along its slant. Its scale
        // grows with the taps' distance (|i| + |j| taps: 1 to 4).
        constexpr double perTaps[5] = {0, 1, 1.0 / 2, 1.0 / 3, 1.0 / 4};
        const double predicted =
            p.depth + (p.depthGradient[0] * i + p.depthGradient[1] * j) * step_;
        const double depth =
            std::abs(g_.depth[q] - predicted) * p.perDepth * perTaps[std::abs(i) + std::abs(j)];
        const double visibility = std::abs(p.visibility - g_.visibility[q]) * p.perVisibility;
        const double occlusion = std::abs(p.occlusion - g_.occlusion[q]) * p.perOcclusion;
        const double albedo = std::abs(p.albedo - g_.albedo[q]) * p.perAlbedo;
        const double luminance = std::abs(p.luminance - luma_[q]) * p.perLuminance;
        return normal + depth + visibility + occlusion + albedo + luminance;
    }

    const Guides& g_;
    int step_;
    bool glossPass_;  ///< the gloss: no albedo guide
    const std::vector<float>& light_;
    const std::vector<float>& variance_;
    const DenoiseOptions& o_;
    std::vector<float> noise_;  ///< the variance blurred
    std::vector<double> luma_;  ///< the signal's luminance per pixel
    int squarings_;             ///< normalExponent = 2^squarings_, or -1
};

/// The passes over one component of the radiance and its variance, in place.
void filter(const Guides& g, std::vector<float>& light, std::vector<float>& variance,
            const DenoiseOptions& options, bool gloss) {
    std::vector<float> lightNext(light.size()), varianceNext(variance.size());
    for (int k = 0; k < options.passes; ++k) {
        const Pass pass(g, 1 << k, light, variance, options, gloss);
        parallelTiles(size_t(g.height), options.threads, [&](size_t y) {
            for (int x = 0; x < g.width; ++x) pass.pixel(x, int(y), lightNext, varianceNext);
        });
        light.swap(lightNext);
        variance.swap(varianceNext);
    }
}

}  // namespace

std::string denoiseDescription(const DenoiseOptions& o) {
    return "edge-avoiding a-trous wavelet, " + std::to_string(o.passes) +
           " passes, diffuse (over the albedo) and gloss apart, guided by albedo, normal, depth, "
           "visibility, occlusion and variance (sigma luminance " +
           std::to_string(o.sigmaLuminance) + ", normal exponent " +
           std::to_string(o.normalExponent) + ", sigma depth " + std::to_string(o.sigmaDepth) +
           ", sigma visibility " + std::to_string(o.sigmaVisibility) + ", sigma occlusion " +
           std::to_string(o.sigmaOcclusion) + ", sigma albedo " + std::to_string(o.sigmaAlbedo) +
           ")";
}

void denoiseFilm(Film& film, const DenoiseOptions& options) {
    if (film.firstRow != 0 || film.rows != film.height)
        throw std::invalid_argument("denoise: the film must hold the whole frame");
    if (options.passes < 0 || options.passes > 12)
        throw std::invalid_argument("denoise: 0 to 12 passes");
    const Guides g = guidesOf(film, options);
    const size_t n = size_t(film.width) * film.height;
    // The diffuse part demodulated: the illumination, and its variance (the luminance's, over
    // the albedo's luminance squared). The rest (a coat's gloss) as it is.
    std::vector<float> light(3 * n), variance(n), gloss(3 * n), glossVariance(n);
    for (size_t i = 0; i < n; ++i) {
        for (int c = 0; c < 3; ++c) {
            light[3 * i + c] = film.diffuse[3 * i + c] / g.demodulate[3 * i + c];
            gloss[3 * i + c] = film.rgb[3 * i + c] - film.diffuse[3 * i + c];
        }
        const double a = g.albedo[i];
        variance[i] = float(film.variance[i] / (a * a));
        glossVariance[i] = film.variance[i];
    }
    filter(g, light, variance, options, false);
    filter(g, gloss, glossVariance, options, true);
    for (size_t i = 0; i < n; ++i)
        if (g.hit[i])
            for (int c = 0; c < 3; ++c) {
                film.diffuse[3 * i + c] = light[3 * i + c] * g.demodulate[3 * i + c];
                film.rgb[3 * i + c] = film.diffuse[3 * i + c] + gloss[3 * i + c];
            }
    for (size_t i = 0; i < n; ++i) {
        const double a = g.albedo[i];
        film.variance[i] = float(variance[i] * a * a + glossVariance[i]);
    }
}

}  // namespace nenrin
