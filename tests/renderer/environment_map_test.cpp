#include "renderer/environment_map.h"

#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <string>

#include "util/input_error.h"

namespace nenrin {
namespace {

constexpr double kPi = std::numbers::pi;

using Texel = std::array<float, 3>;

/// Writes a float EXR lat-long test map into the test temporary folder and returns its path.
std::string writeMap(const std::string& name, int width, int height,
                     const std::function<Texel(int, int)>& texel, int channels = 3) {
    std::string path = ::testing::TempDir() + "nenrin_env_" + name + ".exr";
    OIIO::ImageBuf buf(OIIO::ImageSpec(width, height, channels, OIIO::TypeDesc::FLOAT));
    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i) {
            Texel t = texel(i, j);
            buf.setpixel(i, j, t.data(), channels);
        }
    EXPECT_TRUE(buf.write(path)) << buf.geterror();
    return path;
}

/// The documented mapping, written out independently of the implementation (no rotation).
std::array<int, 2> texelOf(const Vec3& d, int width, int height) {
    double u = 0.5 + std::atan2(d.x, -d.z) / (2 * kPi);
    double v = std::acos(std::clamp(d.y, -1.0, 1.0)) / kPi;
    int i = std::min(static_cast<int>(std::floor(u * width)), width - 1);
    int j = std::min(static_cast<int>(std::floor(v * height)), height - 1);
    return {(i + width) % width, j};
}

/// Calls f(sample) for n x n jittered stratified sample pairs (fixed seed).
void forStratifiedSamples(const EnvironmentMap& map, int n,
                          const std::function<void(const EnvironmentMap::Sample&)>& f) {
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) f(map.sample((a + uniform(rng)) / n, (b + uniform(rng)) / n));
}

/// Checks that sample().pdf equals pdf(direction) and that E[radiance / pdf] over stratified
/// samples equals 4 pi x averageRadiance within `tolerance` (relative, per channel).
void expectUnbiasedEstimate(const EnvironmentMap& map, double tolerance) {
    const int n = 256;
    Rgb sum;
    int mismatches = 0;
    forStratifiedSamples(map, n, [&](const EnvironmentMap::Sample& s) {
        ASSERT_NEAR(length(s.direction), 1.0, 1e-12);
        ASSERT_GT(s.pdf, 0);
        double p = map.pdf(s.direction);
        if (std::abs(p - s.pdf) > 1e-9 * s.pdf) ++mismatches;
        sum = sum + s.radiance * (1 / s.pdf);
    });
    EXPECT_EQ(mismatches, 0);
    Rgb estimate = sum * (1.0 / (n * n)), expected = map.averageRadiance() * (4 * kPi);
    EXPECT_NEAR(estimate.r, expected.r, tolerance * expected.r);
    EXPECT_NEAR(estimate.g, expected.g, tolerance * expected.g);
    EXPECT_NEAR(estimate.b, expected.b, tolerance * expected.b);
}

TEST(EnvironmentMap, ConstantMapIsUniform) {
    const Rgb c{0.5, 1, 2};
    EnvironmentMap map = EnvironmentMap::constant(c);
    EXPECT_TRUE(map.isConstant());
    EXPECT_EQ(map.averageRadiance(), c);
    for (Vec3 d : {Vec3{0, 1, 0}, Vec3{0, 0, -1}, normalize(Vec3{1, -2, 3})}) {
        EXPECT_EQ(map.radiance(d), c);
        EXPECT_DOUBLE_EQ(map.pdf(d), 1 / (4 * kPi));
    }
    Vec3 mean;
    forStratifiedSamples(map, 64, [&](const EnvironmentMap::Sample& s) {
        EXPECT_NEAR(length(s.direction), 1.0, 1e-12);
        EXPECT_DOUBLE_EQ(s.pdf, 1 / (4 * kPi));
        EXPECT_EQ(s.radiance, c);
        mean += s.direction;
    });
    mean = mean / (64.0 * 64.0);
    EXPECT_LT(length(mean), 1e-3);  // stratified uniform directions cancel out
}

TEST(EnvironmentMap, LatLongConventionAndRotation) {
    // 65 x 33 so that a texel centre sits exactly at (u, v) = (0.5, 0.5).
    const int W = 65, H = 33;
    std::string path = writeMap("convention", W, H, [](int i, int j) -> Texel {
        if (j == 0) return {0, 0, 7};              // top row: straight up
        if (j == H - 1) return {1, 0, 0};          // bottom row: straight down
        if (i == 32 && j == 16) return {3, 2, 1};  // image centre: -Z
        if (i == 48 && j == 16) return {0, 5, 0};  // u = 0.75 lies in this texel: +X
        return {0, 0, 0};
    });
    EnvironmentMap map = EnvironmentMap::load(path, 1, 0);
    EXPECT_FALSE(map.isConstant());
    auto expectRgb = [](const Rgb& got, const Rgb& want) {
        EXPECT_NEAR(got.r, want.r, 1e-5);
        EXPECT_NEAR(got.g, want.g, 1e-5);
        EXPECT_NEAR(got.b, want.b, 1e-5);
    };
    expectRgb(map.radiance({0, 0, -1}), {3, 2, 1});
    expectRgb(map.radiance({1, 0, 0}), {0, 0.75 * 5, 0});  // a quarter texel off its centre
    expectRgb(map.radiance({-1, 0, 0}), {0, 0, 0});
    expectRgb(map.radiance({0, 0, 1}), {0, 0, 0});
    expectRgb(map.radiance({0, 1, 0}), {0, 0, 7});
    expectRgb(map.radiance({0, -1, 0}), {1, 0, 0});

    // A quarter turn counter-clockwise seen from above: -Z goes to -X, +X goes to -Z.
    EnvironmentMap turned = EnvironmentMap::load(path, 1, kPi / 2);
    expectRgb(turned.radiance({-1, 0, 0}), {3, 2, 1});
    expectRgb(turned.radiance({0, 0, -1}), {0, 0.75 * 5, 0});
    expectRgb(turned.radiance({1, 0, 0}), {0, 0, 0});
    expectRgb(turned.radiance({0, 1, 0}), {0, 0, 7});

    // Sampling follows the rotation: the centre texel's light now arrives from -X.
    std::string single = writeMap("convention_single", W, H, [](int i, int j) -> Texel {
        return i == 32 && j == 16 ? Texel{1, 1, 1} : Texel{0, 0, 0};
    });
    for (auto [rotation, towards] : {std::pair{0.0, Vec3{0, 0, -1}}, {kPi / 2, Vec3{-1, 0, 0}}}) {
        EnvironmentMap m = EnvironmentMap::load(single, 1, rotation);
        Vec3 mean;
        forStratifiedSamples(m, 32, [&](const EnvironmentMap::Sample& s) { mean += s.direction; });
        mean = normalize(mean);
        EXPECT_GT(dot(mean, towards), 0.999) << mean.x << " " << mean.y << " " << mean.z;
    }
}

TEST(EnvironmentMap, OneBrightTexelDrawsTheSamples) {
    const int W = 64, H = 32, bi = 20, bj = 10;
    std::string path = writeMap("bright", W, H, [](int i, int j) -> Texel {
        return i == bi && j == bj ? Texel{50, 20, 5} : Texel{0, 0, 0};
    });
    EnvironmentMap map = EnvironmentMap::load(path, 1, 0);

    // radiance() is bilinear, so the texel's light reaches half a texel into its neighbours and
    // the samples follow it there: 3/4 x 3/4 of them land in the texel itself, none beyond.
    int inside = 0, outside = 0, total = 0;
    forStratifiedSamples(map, 128, [&](const EnvironmentMap::Sample& s) {
        auto [i, j] = texelOf(s.direction, W, H);
        inside += i == bi && j == bj;
        outside += std::abs(i - bi) > 1 || std::abs(j - bj) > 1;
        ++total;
        EXPECT_NEAR(map.pdf(s.direction), s.pdf, 1e-9 * s.pdf);
    });
    EXPECT_GT(inside, total / 2);
    EXPECT_NEAR(static_cast<double>(inside) / total, 0.5625, 0.01);
    EXPECT_EQ(outside, 0);
    EXPECT_EQ(map.pdf({0, 0, -1}), 0);  // nothing there

    // The mean radiance is the texel's value times its share of the sphere.
    double solidAngle = 2 * kPi / W * (std::cos(kPi * bj / H) - std::cos(kPi * (bj + 1) / H));
    EXPECT_NEAR(map.averageRadiance().r, 50 * solidAngle / (4 * kPi),
                1e-3 * 50 * solidAngle / (4 * kPi));

    expectUnbiasedEstimate(map, 0.01);
}

TEST(EnvironmentMap, SmoothGradientEstimateIsUnbiased) {
    const int W = 128, H = 64;
    std::string path = writeMap("gradient", W, H, [](int i, int j) -> Texel {
        double u = (i + 0.5) / W, v = (j + 0.5) / H;
        return {static_cast<float>(0.2 + 0.8 * u), static_cast<float>(1.5 * (1 - v) + 0.05),
                static_cast<float>(0.6 + 0.5 * std::sin(2 * kPi * u) * std::sin(kPi * v))};
    });
    EnvironmentMap map = EnvironmentMap::load(path, 2.5, 0.7);
    expectUnbiasedEstimate(map, 0.01);

    // pdf() integrates to one over the sphere (uniform stratified directions).
    const int n = 256;
    double integral = 0;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            double cosTheta = 1 - 2 * (a + uniform(rng)) / n,
                   phi = 2 * kPi * (b + uniform(rng)) / n;
            double sinTheta = std::sqrt(1 - cosTheta * cosTheta);
            integral += map.pdf({sinTheta * std::cos(phi), cosTheta, sinTheta * std::sin(phi)});
        }
    EXPECT_NEAR(integral * 4 * kPi / (n * n), 1.0, 0.01);
}

TEST(EnvironmentMap, BlackMapSamplesUniformly) {
    std::string path = writeMap("black", 16, 8, [](int, int) { return Texel{0, 0, 0}; });
    EnvironmentMap map = EnvironmentMap::load(path, 1, 0);
    EXPECT_EQ(map.averageRadiance(), Rgb{});
    forStratifiedSamples(map, 32, [&](const EnvironmentMap::Sample& s) {
        EXPECT_NEAR(s.pdf, 1 / (4 * kPi), 1e-6 / (4 * kPi));
        EXPECT_EQ(map.pdf(s.direction), s.pdf);
        EXPECT_EQ(s.radiance, Rgb{});
    });
}

TEST(EnvironmentMap, GreyIsReplicatedAndScaled) {
    std::string path = writeMap(
        "grey", 8, 4,
        [](int, int) {
            return Texel{0.5f, 0, 0};
        },
        1);
    EnvironmentMap map = EnvironmentMap::load(path, 3, 0);
    EXPECT_EQ(map.radiance({0, 0, -1}), (Rgb{1.5, 1.5, 1.5}));
    EXPECT_NEAR(map.averageRadiance().g, 1.5, 1e-12);
    EXPECT_NEAR(map.pdf(normalize(Vec3{1, 2, 3})), 1 / (4 * kPi), 1e-6);
}

TEST(EnvironmentMap, MissingFileThrowsNamingIt) {
    std::string path = ::testing::TempDir() + "nenrin_env_does_not_exist.exr";
    try {
        EnvironmentMap::load(path, 1, 0);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), path);
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
    }
}

TEST(EnvironmentMap, BadTexelsThrowNamingFileAndPixel) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::string path = writeMap("nan", 8, 4, [&](int i, int j) -> Texel {
        return i == 5 && j == 3 ? Texel{1, nan, 1} : Texel{1, 1, 1};
    });
    try {
        EnvironmentMap::load(path, 1, 0);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), path);
        EXPECT_EQ(e.where(), "pixel (5, 3)");
        EXPECT_NE(e.message().find("channel G"), std::string::npos) << e.message();
    }
    std::string negative = writeMap("negative", 8, 4, [&](int i, int j) -> Texel {
        return i == 2 && j == 1 ? Texel{1, 1, -0.25f} : Texel{1, 1, 1};
    });
    try {
        EnvironmentMap::load(negative, 1, 0);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), negative);
        EXPECT_EQ(e.where(), "pixel (2, 1)");
        EXPECT_NE(e.message().find("negative"), std::string::npos) << e.message();
    }
    std::string two = writeMap(
        "two_channels", 8, 4,
        [](int, int) {
            return Texel{1, 1, 1};
        },
        2);
    EXPECT_THROW(EnvironmentMap::load(two, 1, 0), InputError);
    std::string fine = writeMap("fine", 8, 4, [](int, int) { return Texel{1, 1, 1}; });
    EXPECT_THROW(EnvironmentMap::load(fine, -1, 0), InputError);
}

TEST(EnvironmentMap, ShippedSkyHasZenithHorizonAndGround) {
    EnvironmentMap sky = EnvironmentMap::load(NENRIN_SOURCE_DIR "/scenes/env/sky.exr", 1, 0);
    Rgb zenith = sky.radiance({0, 1, 0}), ground = sky.radiance({0, -1, 0});
    // 0.02 rad above the horizon: between the last two sky rows, short of the ground's row.
    Rgb horizon = sky.radiance({0, std::sin(0.02), -std::cos(0.02)});
    EXPECT_NEAR(zenith.r, 0.25, 0.02);
    EXPECT_NEAR(zenith.g, 0.45, 0.02);
    EXPECT_NEAR(zenith.b, 0.9, 0.02);
    EXPECT_NEAR(horizon.r, 1.0, 0.05);
    EXPECT_NEAR(horizon.b, 1.05, 0.05);
    EXPECT_GT(horizon.b, horizon.r);
    EXPECT_NEAR(ground.r, 0.25, 0.01);
    EXPECT_NEAR(ground.g, 0.22, 0.01);
    EXPECT_NEAR(ground.b, 0.18, 0.01);
    expectUnbiasedEstimate(sky, 0.01);
}

}  // namespace
}  // namespace nenrin
