// FLIP (renderer/image_error/flip.h) against what can be worked out by hand: zero for equal
// images, the colour error of two flat images from CIELAB's published values of the sRGB
// primaries, errors growing with the difference, features raising the error, and HDR-FLIP
// blind to an exposure change of both images.

#include "renderer/image_error/flip.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>

namespace nenrin {
namespace {

FlipImage flat(int w, int h, float r, float g, float b) {
    FlipImage image{w, h, {}};
    for (int i = 0; i < w * h; ++i) image.rgb.insert(image.rgb.end(), {r, g, b});
    return image;
}

double mean(const std::vector<float>& v) {
    return std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
}

/// The colour error of two flat images whose Hunt-adjusted CIELAB distance is `hyab`.
double flatError(double hyab) {
    // sRGB green and blue in CIELAB (D65), the published values; Hunt-adjusted (a, b scaled
    // by L / 100): FLIP's largest colour distance.
    const double green[3] = {87.7347, -86.1827, 83.1793}, blue[3] = {32.3026, 79.1967, -107.8637};
    const double cmax =
        std::pow(std::abs(green[0] - blue[0]) +
                     std::hypot(green[1] * green[0] / 100 - blue[1] * blue[0] / 100,
                                green[2] * green[0] / 100 - blue[2] * blue[0] / 100),
                 0.7);
    const double d = std::pow(hyab, 0.7);
    return d < 0.4 * cmax ? 0.95 / (0.4 * cmax) * d
                          : 0.95 + (d - 0.4 * cmax) / (cmax - 0.4 * cmax) * 0.05;
}

TEST(Flip, EqualImagesHaveNoError) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0, 1);
    FlipImage a{40, 30, {}};
    for (int i = 0; i < 40 * 30 * 3; ++i) a.rgb.push_back(u(rng));
    for (float e : ldrFlip(a, a)) EXPECT_EQ(e, 0.0f);
    for (float e : hdrFlip(a, a, flipExposures(a))) EXPECT_EQ(e, 0.0f);
}

TEST(Flip, FlatImagesGiveTheirColourDistance) {
    // Black against white: L* 0 against 100, no chroma.
    for (float e : ldrFlip(flat(32, 24, 0, 0, 0), flat(32, 24, 1, 1, 1)))
        EXPECT_NEAR(e, flatError(100), 2e-5);
    // Mid grey (sRGB 0.5, L* 53.389) against black.
    for (float e : ldrFlip(flat(32, 24, 0.5f, 0.5f, 0.5f), flat(32, 24, 0, 0, 0)))
        EXPECT_NEAR(e, flatError(53.3890), 2e-4);
    EXPECT_NEAR(flatError(100), 0.96738, 1e-5);  // what `nenrin compare --flip` printed
}

TEST(Flip, LargerDifferencesGiveLargerErrors) {
    std::mt19937 rng(5);
    std::normal_distribution<float> n(0, 1);
    const FlipImage grey = flat(64, 64, 0.5f, 0.45f, 0.4f);
    double last = 0;
    for (float sigma : {0.01f, 0.03f, 0.1f}) {
        FlipImage noisy = grey;
        for (float& v : noisy.rgb) v = std::clamp(v + sigma * n(rng), 0.0f, 1.0f);
        const double m = mean(ldrFlip(grey, noisy));
        EXPECT_GT(m, last) << sigma;
        last = m;
    }
    EXPECT_LT(last, 0.5);
}

TEST(Flip, AnEdgeMissingCountsMoreThanItsColour) {
    // A one-pixel bright line on grey, missing in the test image: at the line the error is
    // raised above the flat error of the same colours (the feature term).
    FlipImage line = flat(33, 33, 0.3f, 0.3f, 0.3f);
    for (int y = 0; y < 33; ++y)
        for (int c = 0; c < 3; ++c) line.rgb[3 * (y * 33 + 16) + c] = 0.9f;
    const std::vector<float> withLine = ldrFlip(line, flat(33, 33, 0.3f, 0.3f, 0.3f));
    const std::vector<float> colourOnly =
        ldrFlip(flat(33, 33, 0.9f, 0.9f, 0.9f), flat(33, 33, 0.3f, 0.3f, 0.3f));
    // The line is thinner than the eye's filters: its colour alone would be a faint error.
    EXPECT_GT(withLine[16 * 33 + 16], 0.5);
    EXPECT_LT(withLine[16 * 33 + 0], 0.05);  // far from the line: nothing
    EXPECT_GT(colourOnly[0], withLine[16 * 33 + 0]);
}

TEST(Flip, HdrFlipIgnoresAnExposureOfBothImages) {
    std::mt19937 rng(7);
    std::lognormal_distribution<float> sky(-1, 1.5);
    FlipImage a{48, 32, {}}, b{48, 32, {}};
    for (int i = 0; i < 48 * 32 * 3; ++i) {
        a.rgb.push_back(sky(rng));
        b.rgb.push_back(a.rgb.back() * (1 + 0.2f * std::sin(float(i))));
    }
    const FlipExposures e = flipExposures(a);
    EXPECT_LT(e.start, e.stop);
    EXPECT_EQ(e.count, std::max(2, int(std::ceil(e.stop - e.start))));
    FlipImage a4 = a, b4 = b;
    for (float& v : a4.rgb) v *= 4;
    for (float& v : b4.rgb) v *= 4;
    const FlipExposures e4 = flipExposures(a4);
    EXPECT_NEAR(e4.start, e.start - 2, 1e-9);
    EXPECT_NEAR(e4.stop, e.stop - 2, 1e-9);
    const std::vector<float> m = hdrFlip(a, b, e), m4 = hdrFlip(a4, b4, e4);
    for (size_t i = 0; i < m.size(); ++i) EXPECT_NEAR(m[i], m4[i], 1e-5);
    EXPECT_GT(mean(m), 0.01);
}

TEST(Flip, BadInputsAreRefused) {
    EXPECT_THROW(ldrFlip(flat(4, 4, 0, 0, 0), flat(4, 5, 0, 0, 0)), std::invalid_argument);
    EXPECT_THROW(ldrFlip(flat(4, 4, 0, 0, 0), flat(4, 4, 0, 0, 0), 0), std::invalid_argument);
    const FlipExposures black = flipExposures(flat(4, 4, 0, 0, 0));
    EXPECT_EQ(black.start, 0);
    EXPECT_EQ(black.stop, 0);
}

}  // namespace
}  // namespace nenrin
