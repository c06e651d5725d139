// nenrin render --denoise and nenrin denoise (renderer/denoise): the same pixels either way,
// the image marked as denoised, a split part and an image denoised twice refused; the wood's
// fine texture kept against a 4096-spp render.

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

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

TEST_F(DenoiseCliTest, ARenderFromBeforeTheNewerAovsIsDenoisedWithNotes) {
    auto r =
        run({"render", kScene.string(), "-q", "--res", "48x32", "--spp", "4", "-o", "new.exr"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    // The same render as an older nenrin wrote it: without visibility, occlusion and diffuse.
    OIIO::ImageBuf render((out_ / "new.exr").string());
    const std::vector<std::string> newer = {"visibility", "occlusion", "diffuse.R", "diffuse.G",
                                            "diffuse.B"};
    std::vector<int> keep;
    for (int c = 0; c < render.nchannels(); ++c)
        if (std::find(newer.begin(), newer.end(), render.spec().channelnames[size_t(c)]) ==
            newer.end())
            keep.push_back(c);
    ASSERT_EQ(keep.size() + newer.size(), size_t(render.nchannels()));
    OIIO::ImageBuf old = OIIO::ImageBufAlgo::channels(render, int(keep.size()), keep);
    ASSERT_TRUE(old.write((in_ / "old.exr").string()));
    auto d = run({"denoise", (in_ / "old.exr").string(), "-o", "old-denoised.exr"});
    ASSERT_EQ(d.exitCode, 0) << d.err;
    for (const char* aov : {"visibility", "occlusion", "diffuse"})
        EXPECT_NE(d.out.find(std::string("has no ") + aov + " AOV"), std::string::npos) << d.out;
    auto out = readImage(out_ / "old-denoised.exr");
    ASSERT_TRUE(out);
    // Filled in as no shadow edge, no corner, all light diffuse (so R = diffuse.R denoised).
    const int v = channelIndex(out->spec, "visibility"), o = channelIndex(out->spec, "occlusion");
    const int red = channelIndex(out->spec, "R"), diffuseRed = channelIndex(out->spec, "diffuse.R");
    ASSERT_GE(std::min({v, o, red, diffuseRed}), 0);
    for (size_t i = 0; i < out->pixels.size(); i += size_t(out->spec.nchannels)) {
        ASSERT_EQ(out->pixels[i + size_t(v)], 1.0f);
        ASSERT_EQ(out->pixels[i + size_t(o)], 0.0f);
        ASSERT_EQ(out->pixels[i + size_t(red)], out->pixels[i + size_t(diffuseRed)]);
    }
    // Its spp (which tells the visibility's noise) must be a count.
    old.specmod().attribute("nenrin:spp", "many");
    ASSERT_TRUE(old.write((in_ / "bad-spp.exr").string()));
    fs::remove(out_ / "new.exr");
    fs::remove(out_ / "old-denoised.exr");
    expectInputError(run({"denoise", (in_ / "bad-spp.exr").string(), "-o", "x.exr"}),
                     {"bad-spp.exr", "nenrin:spp", "many"});
}

/// The second line of `nenrin stats IMAGE --against REF --json`: IMAGE's figures against REF's.
nlohmann::json againstReference(const RunResult& r) {
    std::istringstream lines(r.out);
    std::string line;
    std::getline(lines, line);
    std::getline(lines, line);
    return nlohmann::json::parse(line)["vs"];
}

TEST_F(DenoiseCliTest, KeepsTheWoodsFineTextureOfA4096SppRender) {
    // Issue 34: a 10 cm close-up of table-top-room's oiled top (256 x 256, a glue line across
    // it); the reference is the same view at 4096 spp with another seed (how it was made:
    // tests/data/ref/README.md). The grain lives in the albedo guide, so the denoised 16-spp
    // image must have the reference's fine texture energy within 5 %, where the noise alone
    // adds some 20 %.
    const fs::path reference = kSourceDir / "tests/data/ref/table-top-closeup-4096spp.png";
    const std::vector<std::string> render = {"render",
                                             (kSourceDir / "scenes/table-top-room.json").string(),
                                             "-q",
                                             "--res",
                                             "256x256",
                                             "--spp",
                                             "16",
                                             "--seed",
                                             "7",
                                             "--set",
                                             "/camera/position=[0.1,0.90,0.16]",
                                             "--set",
                                             "/camera/look_at=[0.1,0.744,0.06]",
                                             "--set",
                                             "/camera/fov=40"};
    auto figures = [&](const std::string& name, bool denoise) {
        std::vector<std::string> a = render;
        for (const char* x : {"-o", "x.exr", "--png"}) a.push_back(x);
        a.push_back(name);
        if (denoise) a.push_back("--denoise");
        const RunResult r = run(a);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        fs::remove(out_ / "x.exr");
        const RunResult s =
            run({"stats", (out_ / name).string(), "--against", reference.string(), "--json"});
        EXPECT_EQ(s.exitCode, 0) << s.err;
        return againstReference(s);
    };
    const nlohmann::json noisy = figures("noisy.png", false),
                         denoised = figures("denoised.png", true);
    EXPECT_GT(noisy["fine_ratio"].get<double>(), 1.1) << noisy;  // the noise the test must see
    EXPECT_NEAR(denoised["fine_ratio"].get<double>(), 1.0, 0.05)
        << denoised;  // measured 1.003 (1.034 before the diffuse AOV)
    EXPECT_NEAR(denoised["mid_ratio"].get<double>(), 1.0, 0.05) << denoised;  // 0.998
    EXPECT_LT(denoised["dE_ab"].get<double>(), 0.5) << denoised;              // 0.00
    // 0.90 (noisy 0.19): the denoiser keeps what its albedo guide holds. (0.77 while a pixel's
    // wood was shaded at its 16 samples' mean point, which wandered with the samples and
    // moved the oak's sub-pixel vessels under it: isotropic noise in the guide.)
    EXPECT_GT(denoised["fine_aniso_ratio"].get<double>(), 0.85) << denoised;
}

/// The "FLIP mean" that `nenrin compare A B --flip` prints.
double flipMean(const RunResult& r) {
    const size_t at = r.out.find("FLIP mean ");
    EXPECT_NE(at, std::string::npos) << r.out;
    return at == std::string::npos ? 1.0 : std::stod(r.out.substr(at + 10));
}

TEST_F(DenoiseCliTest, Denoised32SppIsNearerA4096SppRenderThanPlain128Spp) {
    // Issue 34, part 1: a denoised render must reach plain 128 spp's FLIP in a quarter of its
    // time (scripts/bench-noise). 32 spp is a quarter of the samples, so the denoised 32-spp
    // render must be the nearer of the two to the reference (table-top-room at 320 x 200 and
    // 4096 spp, tests/data/ref/README.md). Measured 0.01124 against 0.01174 (0.01185 against
    // 0.01192 while the wood was shaded at its samples' mean point: a change to the look can
    // take this away unnoticed, as that one did).
    const fs::path reference = kSourceDir / "tests/data/ref/table-top-room-4096spp.exr";
    auto flip = [&](const std::string& spp, bool denoise) {
        std::vector<std::string> a = {
            "render",  (kSourceDir / "scenes/table-top-room.json").string(),
            "-q",      "--res",
            "320x200", "--spp",
            spp,       "-o",
            "x.exr"};
        if (denoise) a.push_back("--denoise");
        const RunResult r = run(a);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        const RunResult c =
            run({"compare", reference.string(), (out_ / "x.exr").string(), "--flip"});
        EXPECT_EQ(c.exitCode, 0) << c.err;
        fs::remove(out_ / "x.exr");
        return flipMean(c);
    };
    const double denoised = flip("32", true), plain = flip("128", false);
    EXPECT_LT(denoised, plain) << "denoised 32 spp " << denoised << ", plain 128 spp " << plain;
    EXPECT_GT(plain, 0.005) << plain;  // the reference is another render, not this one
}

}  // namespace
}  // namespace nenrin
