// The photographed spruce strip (data/colour-bars, Larsson et al. 2022) read as a ring colour
// profile: its rings, their statistics and its early and late wood as measured in
// design/fidelity.md (40 rings, width CV 0.52, lag-1 autocorrelation 0.68, early wood
// L*a*b* about 87/3/14, late wood about 74/9/18).

#include "grain/colour_strip.h"

#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "grain/growth_terms.h"
#include "util/input_error.h"

namespace nenrin {
namespace {

std::vector<Rgb> stripColumns(const std::string& path) {
    OIIO::ImageBuf image(path);
    EXPECT_TRUE(image.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << image.geterror();
    const auto& spec = image.spec();
    std::vector<Rgb> columns(size_t(spec.width));
    std::vector<float> px(size_t(spec.nchannels));
    for (int x = 0; x < spec.width; ++x) {
        Rgb sum;
        for (int y = 0; y < spec.height; ++y) {
            image.getpixel(x, y, px.data(), spec.nchannels);
            sum = sum + linearFromSrgb({px[0], px[1], px[2]});
        }
        columns[size_t(x)] = sum * (1.0 / spec.height);
    }
    return columns;
}

TEST(ColourStrip, ThePhotographedSpruceStripHasItsMeasuredRingsAndColours) {
    const std::string path =
        std::string(NENRIN_SOURCE_DIR) + "/data/colour-bars/spruce_bar_color.bmp";
    ColourStrip s = analyseColourStrip(stripColumns(path), path);
    std::printf(
        "strip: %d rings, width CV %.2f, AR1 %.2f; early %.1f/%.1f/%.1f, late %.1f/%.1f/%.1f\n",
        s.rings, s.widthStatistics.cv, s.widthStatistics.autocorrelation, s.early.L, s.early.a,
        s.early.b, s.late.L, s.late.a, s.late.b);
    // Our reading against design/fidelity.md's: 42 rings, CV 0.54, AR1 0.81 (the trend from
    // wide juvenile rings weighs more with our ring boundaries), early and late wood within
    // 2.5 and 3.4 dE*ab of its figures.
    EXPECT_NEAR(s.rings, 40, 3);
    EXPECT_NEAR(s.widthStatistics.cv, 0.52, 0.12);
    EXPECT_NEAR(s.widthStatistics.autocorrelation, 0.68, 0.2);
    EXPECT_LT(deltaE(s.early, {87, 3, 14}), 4.0);
    EXPECT_LT(deltaE(s.late, {74, 9, 18}), 4.0);
    // Spruce's transition is gradual: flat early wood over the first half, then E climbs to
    // the late-wood line over many bins (0.2 -> 0.8 within 0.67 … 0.9 of the ring here).
    ASSERT_EQ(s.lateWoodProfile.size(), 33u);
    const auto& e = s.lateWoodProfile;
    EXPECT_LT(*std::min_element(e.begin(), e.begin() + 16), 0.15);
    EXPECT_GT(*std::max_element(e.begin() + 24, e.end()), 0.8);
    int climbing = 0;
    for (double v : e) climbing += v > 0.2 && v < 0.8;
    EXPECT_GE(climbing, 5);  // more than a sixth of the ring: not an abrupt step
    // The heartwood zone is warmer than the sapwood (the strip's README).
    EXPECT_GT(s.heartwoodOffset.r - s.heartwoodOffset.b, s.sapwoodOffset.r - s.sapwoodOffset.b);
}

TEST(ColourStrip, AShortOrRinglessStripIsRefused) {
    EXPECT_THROW(analyseColourStrip(std::vector<Rgb>(10, Rgb{0.5, 0.4, 0.3}), "short.png"),
                 InputError);
    EXPECT_THROW(analyseColourStrip(std::vector<Rgb>(400, Rgb{0.5, 0.4, 0.3}), "flat.png"),
                 InputError);
}

TEST(ColourStrip, AMeasuredProfileDrivesTheLateWoodFraction) {
    LateWoodShape shape;
    shape.table = {0, 0.2, 1};
    EXPECT_NEAR(lateWoodFraction(7.25, shape), 0.1, 1e-12);
    EXPECT_NEAR(lateWoodFraction(7.75, shape), 0.6, 1e-12);
}

}  // namespace
}  // namespace nenrin
