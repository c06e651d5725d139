#include "renderer/stats/image_statistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "renderer/exr_file.h"
#include "renderer/png_file.h"
#include "renderer/stats/photo_lab.h"
#include "renderer/stats/stats_image.h"
#include "tests/scratch_path.h"
#include "util/hash.h"
#include "util/input_error.h"

namespace nenrin {
namespace {

namespace fs = std::filesystem;

/// L*, a*, b* planes of a lightness pattern (a* = b* = 0).
std::array<Plane, 3> lightnessOnly(const Plane& lightness) {
    return {lightness, Plane(lightness.width, lightness.height),
            Plane(lightness.width, lightness.height)};
}

/// Stripes of period `period` px whose normal is `degrees` off the x axis.
Plane stripes(double period, double degrees) {
    const double a = degrees * std::numbers::pi / 180;
    Plane p(kStatsSize, kStatsSize);
    for (int y = 0; y < p.height; ++y)
        for (int x = 0; x < p.width; ++x)
            p.at(x, y) = 60 + 10 * std::sin(2 * std::numbers::pi *
                                            (x * std::cos(a) + y * std::sin(a)) / period);
    return p;
}

// Ruler-straight stripes: one grain direction everywhere, and fine texture that is all
// direction.
TEST(ImageStatistics, StraightStripesHaveNoDirectionSpreadAndDirectionalFineTexture) {
    for (double degrees : {0.0, 30.0, 90.0}) {
        const ImageStatistics s = imageStatistics(lightnessOnly(stripes(5, degrees)));
        // Along an axis exactly 0; tilted, the reflected borders bend the stripes a little.
        EXPECT_LT(s.dirSpread, degrees == 30 ? 3 : 1e-6) << degrees << " deg";
        EXPECT_GT(s.fineAniso, 50) << degrees << " deg";
        EXPECT_GT(s.fine, 5) << degrees << " deg";  // a period of 5 px is fine texture
    }
}

// White noise is the same in every direction: fine_aniso near 1 (its estimate over a 16 px
// Gaussian is a little above), and the grain direction is all over the place.
TEST(ImageStatistics, UniformNoiseHasFineAnisotropyNearOne) {
    SplitMix rng(7);
    Plane noise(kStatsSize, kStatsSize);
    for (double& v : noise.values) v = 50 + 20 * rng.uniform();
    const ImageStatistics s = imageStatistics(lightnessOnly(noise));
    EXPECT_GT(s.fineAniso, 1.0);
    EXPECT_LT(s.fineAniso, 1.2);
    EXPECT_GT(s.dirSpread, 40);
    EXPECT_NEAR(s.stdL, 20 / std::sqrt(12.0), 0.2);
}

// The colour-and-energy figures are the full set's to the bit, less dir_spread and fine_aniso
// (left 0): the fit compares bake after bake by them alone.
TEST(ImageStatistics, ColourAndEnergyFiguresAreTheFullSetsWithoutTheDirections) {
    SplitMix rng(11);
    std::array<Plane, 3> lab = lightnessOnly(stripes(9, 20));
    for (double& v : lab[0].values) v += 5 * rng.uniform();
    for (double& v : lab[1].values) v = 10 + rng.uniform();
    const ImageStatistics all = imageStatistics(lab);
    const ImageStatistics some = imageStatistics(lab, Figures::kColourAndEnergy);
    for (size_t c = 0; c < 3; ++c) EXPECT_EQ(some.lab[c], all.lab[c]);
    EXPECT_EQ(some.stdL, all.stdL);
    EXPECT_EQ(some.fine, all.fine);
    EXPECT_EQ(some.mid, all.mid);
    EXPECT_GT(all.fineAniso, 1);
    EXPECT_GT(all.dirSpread, 0);
    EXPECT_EQ(some.fineAniso, 0);
    EXPECT_EQ(some.dirSpread, 0);
}

/// Writes a constant 8-bit PNG of `w` x `h` pixels.
fs::path constantPng(const std::string& name, int w, int h, std::array<uint8_t, 3> rgb) {
    const fs::path path = scratchPath(name);
    std::vector<uint8_t> pixels;
    for (int i = 0; i < w * h; ++i) pixels.insert(pixels.end(), rgb.begin(), rgb.end());
    writePng8(path.string(), path.string(), w, h, pixels, {});
    return path;
}

// A constant image's mean colour is the script's formula of its colour (values from
// photo-stats' to_lab), texture figures 0; through the resize too (a normalised filter).
TEST(ImageStatistics, AConstantImagesLabIsTheFormulas) {
    for (int side : {256, 100}) {
        const fs::path png = constantPng("nenrin-stats-constant.png", side, side, {200, 150, 100});
        const ImageStatistics s = imageStatistics(labPlanes(readStatsRgb(png.string()).linear));
        fs::remove(png);
        EXPECT_NEAR(s.lab[0], 65.75812596, 1e-4) << side;  // pixels are float
        EXPECT_NEAR(s.lab[1], 12.76240234, 1e-4) << side;  // pixels are float
        EXPECT_NEAR(s.lab[2], 33.55773023, 1e-4) << side;  // pixels are float
        EXPECT_NEAR(s.stdL, 0, 1e-9);
        EXPECT_NEAR(s.fine, 0, 1e-9);
        EXPECT_NEAR(s.mid, 0, 1e-9);
        EXPECT_NEAR(s.dirSpread, 0, 1e-9);
    }
    // Linear (EXR) colours, above and below the cube-root knee.
    auto lab = photoLabFromLinear(0.2, 0.3, 0.4);
    EXPECT_NEAR(lab[0], 60.42341119, 1e-6);
    EXPECT_NEAR(lab[1], -4.02275975, 1e-6);
    EXPECT_NEAR(lab[2], -13.80297144, 1e-6);
    lab = photoLabFromLinear(0.001, 0.002, 0.003);
    EXPECT_NEAR(lab[0], 1.6797618, 1e-6);
    EXPECT_NEAR(lab[1], -0.40306068, 1e-6);
    EXPECT_NEAR(lab[2], -1.55108036, 1e-6);
}

// EXR colours are linear, clipped at 0 before anything else.
TEST(ImageStatistics, ExrColoursAreLinearAndClippedAtZero) {
    const fs::path exr = scratchPath("stats-linear.exr");
    std::vector<float> pixels;
    for (int i = 0; i < 64 * 64; ++i) pixels.insert(pixels.end(), {0.2f, 0.3f, -0.4f});
    writeFloatExr(exr.string(), exr.string(), 64, 64, {"R", "G", "B"}, pixels.data(), {});
    const StatsRgb rgb = readStatsRgb(exr.string());
    fs::remove(exr);
    EXPECT_EQ(rgb.sourceWidth, 64);
    ASSERT_EQ(rgb.linear[0].width, kStatsSize);
    EXPECT_NEAR(rgb.linear[0].at(100, 100), 0.2, 1e-6);
    EXPECT_NEAR(rgb.linear[2].at(3, 200), 0, 1e-9);
}

// numpy searchsorted on the cumulative weights: the first value reaching half the weight.
TEST(ImageStatistics, WeightedMedianTakesTheFirstValueReachingHalfTheWeight) {
    EXPECT_DOUBLE_EQ(weightedMedian({3, 1, 2}, {1, 1, 1}), 2);
    EXPECT_DOUBLE_EQ(weightedMedian({1, 2}, {1, 1}), 1);  // cumulative 1 reaches 2 / 2
    EXPECT_DOUBLE_EQ(weightedMedian({1, 2, 30}, {1, 1, 5}), 30);
    EXPECT_DOUBLE_EQ(weightedMedian({5, 9}, {0, 0}), 5);
}

// Rings that are the growth time's iso-lines agree everywhere; rings across them nowhere.
TEST(ImageStatistics, RingsAlongTheGrowthTimeAgree) {
    Plane t(kStatsSize, kStatsSize);
    for (int y = 0; y < t.height; ++y)
        for (int x = 0; x < t.width; ++x) t.at(x, y) = 0.3 * x;  // rings are columns
    const RingAgreement along = ringAgreement(stripes(12, 0), t, "photo.png");
    EXPECT_LT(along.medianDeg, 1);
    EXPECT_GT(along.within15, 0.99);
    const RingAgreement across = ringAgreement(stripes(12, 90), t, "photo.png");
    EXPECT_GT(across.medianDeg, 89);
    EXPECT_LT(across.within15, 0.01);
    EXPECT_THROW(ringAgreement(Plane(kStatsSize, kStatsSize, 50), t, "flat.png"), InputError);
    // From the photo's structure, measured once (as the fit does): a flat photo refused too.
    EXPECT_THROW(ringAgreement(grainStructure(Plane(kStatsSize, kStatsSize, 50)), t, "flat.png"),
                 InputError);
}

TEST(ImageStatistics, RatiosAreTakenOfTheReportedFigures) {
    ImageStatistics photo{{80, 10, 20}, 5, 2.5, 1.25, 20, 2};
    ImageStatistics image{{83, 14, 20}, 5, 3, 1, 25.5, 3};
    const StatisticsAgainst a = statisticsAgainst(image, photo, "photo.png");
    EXPECT_DOUBLE_EQ(a.dE, 5);
    EXPECT_DOUBLE_EQ(a.fineRatio, 1.2);
    EXPECT_DOUBLE_EQ(a.midRatio, 0.8);
    EXPECT_DOUBLE_EQ(a.dirSpreadDiff, 5.5);
    EXPECT_DOUBLE_EQ(a.fineAnisoRatio, 1.5);
    photo.fine = 0;
    EXPECT_THROW(statisticsAgainst(image, photo, "photo.png"), InputError);
    const ImageStatistics r = roundedAsReported({{1.234, 2.345, 3.456}, 1.2345, 0, 0, 1.234, 2e4});
    EXPECT_DOUBLE_EQ(r.lab[0], 1.23);
    EXPECT_DOUBLE_EQ(r.stdL, 1.234);  // as Python: 1.2345 is stored a little below
    EXPECT_DOUBLE_EQ(r.fineAniso, 1e4);
}

}  // namespace
}  // namespace nenrin
