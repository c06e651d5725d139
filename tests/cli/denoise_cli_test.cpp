// nenrin render --denoise and nenrin denoise (renderer/denoise): the same pixels either way,
// the image marked as denoised, a split part and an image denoised twice refused.

#include <gtest/gtest.h>

#include "tests/cli/cli_fixture.h"

namespace nenrin {
namespace {

const fs::path kScene = kSourceDir / "tests/data/scenes/small-glulam.json";

class DenoiseCliTest : public CliTest {};

TEST_F(DenoiseCliTest, RenderDenoiseEqualsDenoisingTheRender) {
    const std::vector<std::string> render = {
        "render", kScene.string(), "-q", "--res", "48x32", "--spp", "4", "--threads", "2"};
    auto args = [&](std::vector<std::string> extra) {
        std::vector<std::string> a = render;
        a.insert(a.end(), extra.begin(), extra.end());
        return a;
    };
    auto r = run(args({"-o", "plain.exr"}));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto d = run(args({"-o", "denoised.exr", "--denoise"}));
    ASSERT_EQ(d.exitCode, 0) << d.err;
    EXPECT_NE(d.out.find("denoised in"), std::string::npos) << d.out;
    auto c = run({"denoise", (out_ / "plain.exr").string(), "-o", "after.exr", "--threads", "1"});
    ASSERT_EQ(c.exitCode, 0) << c.err;
    auto plain = readImage(out_ / "plain.exr"), denoised = readImage(out_ / "denoised.exr"),
         after = readImage(out_ / "after.exr");
    ASSERT_TRUE(plain && denoised && after);
    EXPECT_EQ(denoised->pixels, after->pixels);  // every channel, bit for bit
    EXPECT_NE(denoised->pixels, plain->pixels);
    EXPECT_NE(after->spec.get_string_attribute("nenrin:denoised"), "");
    EXPECT_EQ(plain->spec.get_string_attribute("nenrin:denoised"), "");
    // Denoised twice, or a part of a split render alone: refused.
    fs::remove(out_ / "plain.exr");
    fs::rename(out_ / "after.exr", in_ / "after.exr");
    fs::rename(out_ / "denoised.exr", in_ / "denoised.exr");
    expectInputError(run({"denoise", (in_ / "after.exr").string(), "-o", "again.exr"}),
                     {"after.exr", "denoised already"});
    expectInputError(run(args({"-o", "part.exr", "--tile", "1/2", "--denoise"})),
                     {"--denoise", "nenrin denoise"});
    expectInputError(run({"denoise", kScene.string(), "-o", "x.exr"}), {"small-glulam.json"});
}

}  // namespace
}  // namespace nenrin
