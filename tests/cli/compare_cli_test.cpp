// nenrin compare --flip: the FLIP error of B against A (renderer/image_error/flip.h), LDR for
// 8-bit images and HDR for float ones, its map, and --max-flip failing the comparison.

#include <gtest/gtest.h>

#include "tests/cli/cli_fixture.h"

namespace nenrin {
namespace {

class CompareCliTest : public CliTest {
protected:
    /// A flat w x h RGB image of `value`, as 8-bit PNG or float EXR (by the name).
    fs::path flat(const std::string& name, float value) {
        const fs::path path = in_ / name;
        const bool exr = path.extension() == ".exr";
        OIIO::ImageSpec spec(24, 16, 3, exr ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
        std::vector<float> pixels(24 * 16 * 3, value);
        auto out = OIIO::ImageOutput::create(path.string());
        EXPECT_TRUE(out && out->open(path.string(), spec) &&
                    out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
        if (out) out->close();
        return path;
    }
};

TEST_F(CompareCliTest, FlipOfBlackAgainstWhite) {
    auto r =
        run({"compare", flat("black.png", 0).string(), flat("white.png", 1).string(), "--flip"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    // L* 0 against 100: the flat-image value worked out in flip_test.cpp.
    EXPECT_NE(r.out.find("FLIP mean 0.96738"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("LDR"), std::string::npos) << r.out;
}

TEST_F(CompareCliTest, FloatImagesGetHdrFlipAndAMap) {
    const fs::path a = flat("a.exr", 0.5f), b = flat("b.exr", 0.4f);
    auto same = run({"compare", a.string(), a.string(), "--flip"});
    ASSERT_EQ(same.exitCode, 0) << same.err;
    EXPECT_NE(same.out.find("FLIP mean 0 "), std::string::npos) << same.out;
    EXPECT_NE(same.out.find("HDR"), std::string::npos) << same.out;
    // Past --max-flip: exit 2, and the map is kept as the report.
    auto r =
        run({"compare", a.string(), b.string(), "--flip-map", "map.exr", "--max-flip", "0.01"});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("FLIP"), std::string::npos) << r.err;
    auto map = readImage(out_ / "map.exr");
    ASSERT_TRUE(map);
    EXPECT_GT(map->pixels[0], 0.01f);
    EXPECT_LT(map->pixels[0], 1.0f);
    fs::remove(out_ / "map.exr");
    expectInputError(run({"compare", a.string(), b.string(), "--flip-map", "map.png"}),
                     {"map.png"});
}

}  // namespace
}  // namespace nenrin
