// The AOV-guided à-trous denoiser on films whose truth is known: noise with a known variance
// over a textured albedo is removed while the texture stays; light does not bleed across a
// normal edge, a shadow's edge or into a corner; a gloss over the texture is filtered apart;
// background pixels are kept; the result is the same for any thread count.

#include "renderer/denoise/atrous_denoiser.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace nenrin {
namespace {

/// A w x h film of a plane facing the camera at depth 2: albedo a fine texture (stripes of
/// two pixels, the grain's scale), light `light(x)` times that albedo, plus Gaussian noise of
/// standard deviation `sigma` per channel (its variance written into the variance AOV, as a
/// render's samples would estimate it). A matte surface: all of it diffuse.
Film noisyFilm(int w, int h, double sigma, uint32_t seed, double (*light)(int x),
               Film* truth = nullptr) {
    Film film;
    film.resize(w, h);
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0, sigma);
    if (truth) truth->resize(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * w + x;
            const double a[3] = {((x / 2 + y / 3) % 2) ? 0.55 : 0.35, 0.3, 0.2};
            for (int c = 0; c < 3; ++c) {
                film.albedo[3 * i + c] = float(a[c]);
                const double clean = a[c] * light(x);
                film.rgb[3 * i + c] = float(clean + noise(rng));
                if (truth) truth->rgb[3 * i + c] = float(clean);
            }
            film.alpha[i] = 1;
            film.depth[i] = 2;
            film.normal[3 * i + 2] = 1;
            // The luminance of the noise: 0.2126^2 + 0.7152^2 + 0.0722^2 of sigma^2.
            film.variance[i] =
                float(sigma * sigma * (0.2126 * 0.2126 + 0.7152 * 0.7152 + 0.0722 * 0.0722));
        }
    film.diffuse = film.rgb;
    return film;
}

double rmse(const Film& a, const Film& b) {
    double s = 0;
    for (size_t i = 0; i < a.rgb.size(); ++i) s += std::pow(a.rgb[i] - b.rgb[i], 2);
    return std::sqrt(s / double(a.rgb.size()));
}

/// The texture's contrast: the mean absolute difference of horizontal neighbours' red.
double texture(const Film& f) {
    double s = 0;
    size_t n = 0;
    for (int y = 0; y < f.height; ++y)
        for (int x = 1; x < f.width; ++x, ++n)
            s += std::abs(f.rgb[3 * (size_t(y) * f.width + x)] -
                          f.rgb[3 * (size_t(y) * f.width + x - 1)]);
    return s / double(n);
}

/// The mean error of column x's green over rows 8..55 (a step's bleed shows there).
double columnError(const Film& film, const Film& truth, int x) {
    double error = 0;
    for (int y = 8; y < 56; ++y) {
        const size_t i = size_t(y) * film.width + x;
        error += (film.rgb[3 * i + 1] - truth.rgb[3 * i + 1]) / 48;
    }
    return error;
}

TEST(Denoise, NoiseGoesAndTheTextureStays) {
    Film truth;
    Film film = noisyFilm(
        96, 64, 0.05, 1, [](int) { return 1.0; }, &truth);
    const double before = rmse(film, truth);
    denoiseFilm(film);
    EXPECT_LT(rmse(film, truth), before / 4) << before;
    // The stripes are the albedo's: carried by the guide, not blurred (within 5 %).
    EXPECT_NEAR(texture(film) / texture(truth), 1, 0.05);
}

TEST(Denoise, LightDoesNotBleedAcrossAnEdge) {
    // Left half lit 1, right half 0.7, the halves turned apart (normals 90 degrees apart):
    // a step the noise alone (sigma 0.05) would let the filter smear; the normals stop it.
    Film truth;
    auto light = [](int x) { return x < 48 ? 1.0 : 0.7; };
    Film film = noisyFilm(96, 64, 0.05, 2, light, &truth);
    for (size_t i = 0; i < film.alpha.size(); ++i)
        if (i % 96 >= 48) {
            film.normal[3 * i] = 1;
            film.normal[3 * i + 2] = 0;
        }
    denoiseFilm(film);  // without the normal weight: 0.012 and 0.015
    // Along the edge, on both sides: the mean error of the row of pixels.
    for (int x : {47, 48}) EXPECT_LT(std::abs(columnError(film, truth, x)), 0.006) << x;
}

TEST(Denoise, AShadowsEdgeStaysSharp) {
    // One plane, its right half in a shadow (light 1 -> 0.6: what the indirect light leaves);
    // only the visibility AOV tells the halves apart.
    Film truth;
    auto light = [](int x) { return x < 48 ? 1.0 : 0.6; };
    Film film = noisyFilm(96, 64, 0.05, 4, light, &truth);
    Film blind = film;  // its visibility says nothing (1 everywhere, as where no light is sampled)
    for (size_t i = 0; i < film.alpha.size(); ++i) film.visibility[i] = i % 96 < 48 ? 1 : 0;
    denoiseFilm(film);
    denoiseFilm(blind);
    for (int x : {47, 48}) {
        EXPECT_LT(std::abs(columnError(film, truth, x)), 0.006) << x;
        EXPECT_GT(std::abs(columnError(blind, truth, x)), 0.012) << x;  // it sees the bleed
    }
}

TEST(Denoise, TheDarkeningIntoACornerIsKept) {
    // A floor meeting a wall at x = 0 (the image's edge): the indirect light darkens towards
    // the corner, 1 - 0.6 exp(-x / 3). Taps reach past the darkening on one side only, so a
    // filter blind to it brightens the corner; the occlusion AOV (how near the first bounce
    // found the wall) tells it apart.
    Film truth;
    auto light = [](int x) { return 1 - 0.6 * std::exp(-x / 3.0); };
    Film film = noisyFilm(96, 64, 0.05, 10, light, &truth);
    Film blind = film;  // as a render from before the AOV: occlusion 0 everywhere
    for (size_t i = 0; i < film.alpha.size(); ++i)
        film.occlusion[i] = float(0.6 * std::exp(-double(i % 96) / 3));
    denoiseFilm(film);
    denoiseFilm(blind);
    // Measured: blind 0.077, 0.043, 0.022 too bright in columns 0, 1, 2; guided 0.008,
    // 0.012, 0.005.
    for (int x : {0, 1, 2}) {
        EXPECT_GT(columnError(blind, truth, x), 0.02) << x;  // brightened
        EXPECT_LT(std::abs(columnError(film, truth, x)), 0.015) << x;
        EXPECT_LT(std::abs(columnError(film, truth, x)), columnError(blind, truth, x) / 3) << x;
    }
}

TEST(Denoise, AGlossOverTheGrainIsFilteredApart) {
    // A coat's gloss, the same 0.3 over pale and dark stripes of albedo, with noise of its
    // own. Divided by the albedo with the rest it would step at every stripe (0.3 / 0.35 vs
    // 0.3 / 0.55) and the albedo guide would stop the filter there; the diffuse AOV keeps it
    // out of the quotient.
    Film truth;
    Film film = noisyFilm(
        96, 64, 0.05, 11, [](int) { return 1.0; }, &truth);
    std::mt19937 rng(12);
    std::normal_distribution<double> noise(0, 0.05);
    const double y2 = 0.2126 * 0.2126 + 0.7152 * 0.7152 + 0.0722 * 0.0722;
    for (size_t i = 0; i < film.alpha.size(); ++i) {
        const double gloss = 0.3 + noise(rng);
        for (int c = 0; c < 3; ++c) {
            film.rgb[3 * i + c] += float(gloss);
            truth.rgb[3 * i + c] += 0.3f;
        }
        film.variance[i] += float(0.05 * 0.05 * y2);
    }
    const double before = rmse(film, truth);
    Film together = film;
    together.diffuse = together.rgb;  // as a render from before the AOV
    denoiseFilm(film);
    denoiseFilm(together);
    // Measured: 0.0705 -> 0.0052 apart, 0.0241 together.
    EXPECT_LT(rmse(film, truth), before / 4) << before;
    EXPECT_LT(rmse(film, truth), 0.5 * rmse(together, truth)) << rmse(together, truth);
    EXPECT_NEAR(texture(film) / texture(truth), 1, 0.05);
}

TEST(Denoise, ANoisyVisibilityDoesNotStopTheFilter) {
    // Many lights, one picked per sample: a half-lit plane's visibility is a share of 32 coin
    // tosses, noise and no edge. Knowing the samples, the filter takes it for noise.
    Film truth;
    Film film = noisyFilm(
        96, 64, 0.05, 6, [](int) { return 1.0; }, &truth);
    std::mt19937 rng(7);
    std::binomial_distribution<int> tosses(32, 0.5);
    for (float& v : film.visibility) v = float(tosses(rng)) / 32;
    const double before = rmse(film, truth);
    Film blind = film;
    DenoiseOptions o;
    o.samples = 32;
    denoiseFilm(film, o);
    denoiseFilm(blind);  // samples unknown: every visibility difference an edge
    EXPECT_LT(rmse(film, truth), before / 4) << before;
    EXPECT_GT(rmse(blind, truth), 1.3 * rmse(film, truth));
}

TEST(Denoise, ASlantedPlaneIsSmoothedAlikeEveryWay) {
    // A wall seen at a slant: its depth grows 2 % of itself per pixel across the image, not
    // at all down it. Depth that follows the plane is no edge in any direction: the noise goes
    // as on a plane facing the camera, and no more along one axis than the other (a filter
    // that took depth steps for edges left vertical streaks on the showroom's walls).
    Film truth;
    Film facing = noisyFilm(
        96, 64, 0.05, 8, [](int) { return 1.0; }, &truth);
    Film slanted = facing;
    for (size_t i = 0; i < slanted.depth.size(); ++i)
        slanted.depth[i] = float(2 * std::pow(1.02, double(i % 96)));
    denoiseFilm(facing);
    denoiseFilm(slanted);
    EXPECT_LT(rmse(slanted, truth), 1.1 * rmse(facing, truth)) << rmse(facing, truth);
    // The residual's neighbour correlation along and across the slant: as on the facing plane
    // (whose stripes of albedo make it differ between the two).
    auto correlation = [&](const Film& f, int dx, int dy) {
        double s = 0, s2 = 0;
        for (int y = 4; y < 60; ++y)
            for (int x = 4; x < 92; ++x) {
                const size_t i = size_t(y) * 96 + x, j = size_t(y + dy) * 96 + x + dx;
                const double a = f.rgb[3 * i + 1] - truth.rgb[3 * i + 1];
                const double b = f.rgb[3 * j + 1] - truth.rgb[3 * j + 1];
                s += a * b;
                s2 += a * a;
            }
        return s / s2;
    };
    EXPECT_NEAR(correlation(slanted, 3, 0), correlation(facing, 3, 0), 0.05);
    EXPECT_NEAR(correlation(slanted, 0, 3), correlation(facing, 0, 3), 0.05);
}

TEST(Denoise, BackgroundIsKeptAndThreadsDoNotMatter) {
    Film film = noisyFilm(64, 48, 0.05, 3, [](int x) { return 0.5 + x / 64.0; });
    for (size_t i = 0; i < film.alpha.size(); i += 7) film.alpha[i] = 0;  // sky seen here
    const Film original = film;
    Film one = film, two = film;
    DenoiseOptions o;
    o.threads = 1;
    denoiseFilm(one, o);
    o.threads = 2;
    denoiseFilm(two, o);
    EXPECT_EQ(one.rgb, two.rgb);
    for (size_t i = 0; i < film.alpha.size(); i += 7)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(one.rgb[3 * i + c], original.rgb[3 * i + c]);
}

TEST(Denoise, APixelWithoutANormalKeepsAFiniteValue) {
    // A hit whose samples' normals cancelled (a thin sheet seen from both sides): no
    // neighbour agrees with it, and it must still keep its own value, not 0 / 0.
    Film film = noisyFilm(32, 32, 0.05, 9, [](int) { return 1.0; });
    const size_t i = 16 * 32 + 16;
    for (int c = 0; c < 3; ++c) film.normal[3 * i + c] = 0;
    denoiseFilm(film);
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(film.rgb[3 * i + c])) << c;
}

TEST(Denoise, APartOfAFrameIsRefused) {
    Film band;
    band.resize(16, 32, 16, 16);
    EXPECT_THROW(denoiseFilm(band), std::invalid_argument);
}

}  // namespace
}  // namespace nenrin
