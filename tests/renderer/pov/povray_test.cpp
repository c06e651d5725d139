// The POV-Ray twins (scenes/povray/): each pair rendered small by nenrin and by POV-Ray 3.7
// with the reference options of docs/design/povray.md, then compared by statistics with written
// thresholds (POV-Ray is another renderer: not per-pixel equality). Measured when written
// (160 x 120): rings RMSE 0.0054 / mean 0.0030; Lambert box 0.0026 / 0.00036; glulam block
// from df3 0.0050 / 0.0016. Skipped, saying so, only if povray is not installed.

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "tests/cli/cli_fixture.h"

namespace {

const fs::path kTwins = kSourceDir / "scenes/povray";

struct Limits {
    double rmse, mean;
};

class PovrayTwinTest : public CliTest {
protected:
    void SetUp() override {
        CliTest::SetUp();
        if (std::system("command -v povray >/dev/null 2>&1") != 0)
            GTEST_SKIP() << "povray is not installed (Debian package povray): twins not checked";
    }

    /// Runs POV-Ray on `pov` inside `folder` (includes and df3 files are relative to it).
    void povray(const fs::path& folder, const fs::path& pov, const fs::path& output) {
        std::string cmd = fmt::format(
            "cd {} && povray -D +FE +WT2 +A0.0 +AM2 +R4 -J +W160 +H120 {} +O{} >{} 2>&1",
            shellQuote(folder.string()), shellQuote(pov.string()), shellQuote(output.string()),
            shellQuote((root_ / "povray.log").string()));
        ASSERT_EQ(std::system(cmd.c_str()), 0) << readText(root_ / "povray.log");
        ASSERT_TRUE(fs::exists(output)) << readText(root_ / "povray.log");
    }

    void expectAgreement(const fs::path& nenrin, const fs::path& pov, Limits limits) {
        OIIO::ImageBuf a(nenrin.string()), b(pov.string());
        auto cmp =
            OIIO::ImageBufAlgo::compare(a, b, 0.02f, 1e30f, OIIO::ROI(0, 160, 0, 120, 0, 1, 0, 3));
        EXPECT_LT(cmp.rms_error, limits.rmse) << "PSNR " << cmp.PSNR;
        EXPECT_LT(cmp.meanerror, limits.mean) << "max " << cmp.maxerror;
        std::printf("%s: RMSE %.5f, mean %.5f, PSNR %.1f dB\n", pov.filename().c_str(),
                    cmp.rms_error, cmp.meanerror, cmp.PSNR);
    }

    fs::path render(const fs::path& scene) {
        fs::path out = out_ / (scene.stem().string() + ".nenrin.exr");
        RunResult r = run({"render", scene.string(), "-q", "-o", out.string()});
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return out;
    }
};

TEST_F(PovrayTwinTest, ConcentricRingsMatchPovRaysWoodPattern) {
    fs::path nenrin = render(kTwins / "rings.json");
    povray(out_, kTwins / "rings.pov", out_ / "rings.pov.exr");
    expectAgreement(nenrin, out_ / "rings.pov.exr", {0.012, 0.006});
}

TEST_F(PovrayTwinTest, LambertBoxUnderADistantLightMatches) {
    fs::path nenrin = render(kTwins / "lambert-box.json");
    fs::path twin = out_ / "box";
    fs::create_directory(twin);
    ASSERT_EQ(run({"pov", (kTwins / "lambert-box.json").string(), "-o", twin.string()}).exitCode,
              0);
    povray(twin, "scene.pov", out_ / "box.pov.exr");
    expectAgreement(nenrin, out_ / "box.pov.exr", {0.006, 0.001});
}

TEST_F(PovrayTwinTest, GlulamBakedToDf3MatchesNenrinsOwnRender) {
    fs::path nenrin = render(kTwins / "glulam-block.json");
    fs::path twin = out_ / "glulam";
    fs::create_directory(twin);
    ASSERT_EQ(run({"pov", (kTwins / "glulam-block.json").string(), "-o", twin.string(), "--volume",
                   "192"})
                  .exitCode,
              0);
    povray(twin, "scene.pov", out_ / "glulam.pov.exr");
    expectAgreement(nenrin, out_ / "glulam.pov.exr", {0.010, 0.003});
}

TEST_F(PovrayTwinTest, CompareExitsNonZeroPastItsLimits) {
    fs::path a = render(kTwins / "lambert-box.json");
    RunResult same = run({"compare", a.string(), a.string(), "--max-rmse", "0"});
    EXPECT_EQ(same.exitCode, 0) << same.err;
    EXPECT_NE(same.out.find("RMSE 0"), std::string::npos) << same.out;
    fs::path b = out_ / "seed2.exr";
    ASSERT_EQ(run({"render", (kTwins / "lambert-box.json").string(), "-q", "--spp", "1", "-o",
                   b.string()})
                  .exitCode,
              0);
    RunResult differ = run({"compare", a.string(), b.string(), "--max-rmse", "1e-9", "--diff",
                            (out_ / "diff.exr").string()});
    EXPECT_EQ(differ.exitCode, 2) << differ.err;
    EXPECT_NE(differ.err.find("RMSE"), std::string::npos) << differ.err;
    EXPECT_TRUE(fs::exists(out_ / "diff.exr"));
}

}  // namespace
