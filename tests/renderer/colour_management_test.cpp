#include "renderer/colour_management.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <optional>
#include <sstream>

#include "util/input_error.h"

namespace nenrin {
namespace {

namespace fs = std::filesystem;

// Every test runs with $OCIO unset (the built-in config) unless it sets it, and the caller's
// environment is put back afterwards.
class ColourManagement : public ::testing::Test {
protected:
    void SetUp() override {
        if (const char* v = getenv("OCIO")) saved_ = v;
        unsetenv("OCIO");
        dir_ = fs::temp_directory_path() /
               ("nenrin-colour-" + std::to_string(getpid()) + "-" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        if (saved_)
            setenv("OCIO", saved_->c_str(), 1);
        else
            unsetenv("OCIO");
        fs::remove_all(dir_);
    }

    std::optional<std::string> saved_;
    fs::path dir_;
};

// The display value of one grey pixel.
int grey8(float v, double exposureStops = 0) {
    float rgb[3] = {v, v, v};
    std::vector<uint8_t> out = toDisplay8(rgb, 1, 1, exposureStops);
    EXPECT_EQ(out.size(), 3u);
    EXPECT_EQ(out[0], out[1]);
    EXPECT_EQ(out[0], out[2]);
    return out[0];
}

std::string inputErrorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST_F(ColourManagement, BuiltInConfigIsTheDefault) {
    EXPECT_EQ(displayConfigName(), "nenrin built-in (share/ocio/nenrin.ocio)");
    setenv("OCIO", "", 1);  // empty means unset, as for OCIO itself
    EXPECT_EQ(displayConfigName(), "nenrin built-in (share/ocio/nenrin.ocio)");
    EXPECT_EQ(grey8(0.18f), 118);
}

TEST_F(ColourManagement, SrgbCurveEndsAndMiddleGrey) {
    EXPECT_EQ(grey8(0.f), 0);
    EXPECT_EQ(grey8(1.f), 255);
    EXPECT_EQ(grey8(0.18f), 118);  // sRGB 0.4613
    // The end of the linear segment: 12.92 x 0.0031308 = 0.04045 -> 10.3.
    EXPECT_NEAR(grey8(0.0031308f), 10, 1);
}

TEST_F(ColourManagement, OutOfRangeAndNonFiniteValuesClip) {
    EXPECT_EQ(grey8(1.5f), 255);
    EXPECT_EQ(grey8(1e30f), 255);
    EXPECT_EQ(grey8(std::numeric_limits<float>::infinity()), 255);
    EXPECT_EQ(grey8(-0.5f), 0);
    EXPECT_EQ(grey8(-std::numeric_limits<float>::infinity()), 0);
    EXPECT_EQ(grey8(std::numeric_limits<float>::quiet_NaN()), 0);
}

TEST_F(ColourManagement, ExposureIsAppliedInStopsFirst) {
    EXPECT_EQ(grey8(0.09f, +1), grey8(0.18f));
    EXPECT_EQ(grey8(0.36f, -1), grey8(0.18f));
    EXPECT_EQ(grey8(0.5f, +1), 255);
}

TEST_F(ColourManagement, ChannelsAndPixelsKeepTheirPlaces) {
    // 2x1: a red pixel, then a blue one.
    const std::vector<float> rgb = {1, 0, 0, 0, 0, 0.18f};
    EXPECT_EQ(toDisplay8(rgb, 2, 1), (std::vector<uint8_t>{255, 0, 0, 0, 0, 118}));
    EXPECT_TRUE(toDisplay8({}, 0, 0).empty());
    EXPECT_THROW(toDisplay8(rgb, 1, 1), std::invalid_argument);
}

TEST_F(ColourManagement, PreviewPngReadsBackWithTheSameBytes) {
    const int w = 5, h = 3;
    std::vector<float> rgb(w * h * 3);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            for (int c = 0; c < 3; ++c) rgb[(j * w + i) * 3 + c] = 0.1f * i + 0.3f * j + 0.05f * c;
    const std::string path = (dir_ / "preview.png").string();
    writePreviewPng(path, rgb, w, h, 0.5);

    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in) << OIIO::geterror();
    EXPECT_EQ(in->format_name(), std::string("png"));
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.width, w);
    EXPECT_EQ(spec.height, h);
    EXPECT_EQ(spec.nchannels, 3);
    std::vector<uint8_t> pixels(w * h * 3);
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, pixels.data()));
    in->close();
    EXPECT_EQ(pixels, toDisplay8(rgb, w, h, 0.5));
    // Only the PNG: the temporary file was renamed, not left behind.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

TEST_F(ColourManagement, PreviewPngRejectsABadPath) {
    const std::vector<float> rgb = {0.5f, 0.5f, 0.5f};
    std::string missing = (dir_ / "no-such-folder" / "p.png").string();
    EXPECT_NE(inputErrorOf([&] { writePreviewPng(missing, rgb, 1, 1); }).find(missing),
              std::string::npos);
    EXPECT_THROW(writePreviewPng(dir_.string(), rgb, 1, 1), InputError);
    EXPECT_THROW(writePreviewPng((dir_ / "p.jpg").string(), rgb, 1, 1), InputError);
    EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(ColourManagement, MissingOcioConfigIsAnInputErrorNamingIt) {
    const std::string path = (dir_ / "missing.ocio").string();
    setenv("OCIO", path.c_str(), 1);
    EXPECT_EQ(displayConfigName(), path);
    const std::vector<float> rgb = {0.18f, 0.18f, 0.18f};
    try {
        toDisplay8(rgb, 1, 1);
        FAIL() << "no InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), path);
        EXPECT_EQ(e.where(), "$OCIO");
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
    // No preview is written either.
    const std::string png = (dir_ / "p.png").string();
    EXPECT_NE(inputErrorOf([&] { writePreviewPng(png, rgb, 1, 1); }).find(path), std::string::npos);
    EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(ColourManagement, GarbageOcioConfigIsAnInputErrorNamingIt) {
    const std::vector<float> rgb = {0.18f, 0.18f, 0.18f};
    const std::pair<const char*, const char*> garbage[] = {
        {"binary.ocio", "\x01\x02 not: [yaml {{\n\tat all: ]"},
        {"not-ocio.ocio", "hello: world\n"},
    };
    for (const auto& [name, text] : garbage) {
        const std::string path = (dir_ / name).string();
        std::ofstream(path) << text;
        setenv("OCIO", path.c_str(), 1);
        std::string msg = inputErrorOf([&] { toDisplay8(rgb, 1, 1); });
        EXPECT_NE(msg.find(path + ": $OCIO: "), std::string::npos) << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
}

TEST_F(ColourManagement, OcioNamingTheShippedConfigGivesTheSameResult) {
    const std::string path = NENRIN_SOURCE_DIR "/share/ocio/nenrin.ocio";
    const std::vector<float> rgb = {0, 0.0031308f, 0.18f, 0.5f, 1, 2};
    std::vector<uint8_t> builtin = toDisplay8(rgb, 2, 1);
    setenv("OCIO", path.c_str(), 1);
    EXPECT_EQ(displayConfigName(), path);
    EXPECT_EQ(toDisplay8(rgb, 2, 1), builtin);
}

TEST_F(ColourManagement, ShippedConfigFileIsTheEmbeddedOne) {
    std::ifstream f(NENRIN_SOURCE_DIR "/share/ocio/nenrin.ocio", std::ios::binary);
    ASSERT_TRUE(f);
    std::stringstream text;
    text << f.rdbuf();
    EXPECT_EQ(text.str(), builtinDisplayConfig())
        << "share/ocio/nenrin.ocio changed since the last CMake run: rebuild";
}

}  // namespace
}  // namespace nenrin
