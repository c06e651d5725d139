// End-to-end tests of absurd numbers (issue 14): each once crashed nenrin (a segfault in the
// growth field, Embree's abort on an invalid ray) or let NaN through; each must now end in a
// clear error, a non-zero exit and no output.

#include "tests/cli/cli_fixture.h"

namespace {

const fs::path kScene = kSourceDir / "tests/data/scenes/small-glulam.json";

class HostileNumbersCliTest : public CliTest {};

TEST_F(HostileNumbersCliTest, AFarAwaySliceIsRefused) {
    for (const char* at : {"1e308", "-2e4"})
        expectInputError(slice({{"--at", at}}), {"--at", "finite number of metres"});
    expectInputError(volume({{"--box", "-0.1,-0.1,0.9,0.1,0.1,1e300"}}), {"--box", "beyond"});
}

TEST_F(HostileNumbersCliTest, HugeSceneValuesAreRefusedWhereTheyAreRead) {
    // A camera at 9e18 m once reached Embree as an invalid ray and aborted the process; a sun
    // of 1e308 made infinite pixels.
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"/camera/position=[9e18,0,1]", "camera.position[0]"},
        {"/lights/0/irradiance=1e308", "lights[0].irradiance"}};
    for (const auto& [set, where] : cases)
        expectInputError(
            run({"render", kScene.string(), "-q", "--set", set, "-o", (out_ / "x.exr").string()}),
            {where, "beyond the +-1e+09"});
}

TEST_F(HostileNumbersCliTest, NanOptionsAreRefusedByTheParser) {
    auto r = run(
        {"render", kScene.string(), "--noise-threshold", "nan", "-o", (out_ / "x.exr").string()});
    expectFailure(r, {"--noise-threshold", "finite"});
    r = run({"compare", kScene.string(), kScene.string(), "--max-rmse", "nan"});
    expectFailure(r, {"--max-rmse", "finite"});
    r = run({"tree", "preview", skeletonScene("conifer.json").string(), "--azimuth", "nan", "-o",
             (out_ / "p.png").string()});
    expectFailure(r, {"--azimuth", "finite"});
}

TEST_F(HostileNumbersCliTest, RangeErrorsAreShort) {
    // CLI11's range check once printed the largest double in full: a 309-digit number.
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"render", kScene.string(), "--noise-threshold", "1e999"},
          {"render", kScene.string(), "--spp", "1e400"},
          {"tree", "kanayama", "--years", "1e999"},
          {"stand", "kunii", "--irradiance", "-1e999"}}) {
        std::vector<std::string> full = args;
        full.insert(full.end(), {"-o", (out_ / "x.json").string()});
        auto r = run(full);
        expectFailure(r, {args[args.size() - 2]});
        EXPECT_LT(r.err.size(), 200u) << r.err;
    }
}

TEST_F(HostileNumbersCliTest, MoreThreadsThanCoresStayQuiet) {
    // --threads 64 once printed TBB's "number of workers is limited" warning through -q.
    auto r = run({"render", kScene.string(), "-q", "--threads", "64", "--spp", "1", "-o",
                  (out_ / "x.exr").string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");
}

TEST_F(HostileNumbersCliTest, TreeYearsHaveOneRangeInHelpAndErrors) {
    // --help said 1-1000 and the model then refused 600 as "[0, 500]", naming <input>.
    for (const char* model : {"kanayama", "hayashi", "akagi"}) {
        auto help = run({"tree", model, "--help"});
        EXPECT_NE(help.out.find("[1 - 500]"), std::string::npos) << model << help.out;
        auto r = run({"tree", model, "--years", "600", "-o", (out_ / "t.json").string()});
        expectFailure(r, {"--years", "600", "1 to 500"});
        EXPECT_EQ(r.err.find("<input>"), std::string::npos) << r.err;
    }
}

TEST_F(HostileNumbersCliTest, CompareRefusesImagesWithNan) {
    // Once: RMSE nan and exit 0, so a broken render passed a regression check.
    const fs::path image = in_ / "nan.exr";
    std::vector<float> pixels = {0.5f, 0.5f, 0.5f, 0.5f, std::nanf(""), 0.5f,
                                 0.5f, 0.5f, 0.5f, 0.5f, 0.5f,          0.5f};
    auto out = OIIO::ImageOutput::create(image.string());
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(image.string(), OIIO::ImageSpec(2, 2, 3, OIIO::TypeDesc::FLOAT)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    out->close();
    expectInputError(run({"compare", image.string(), image.string(), "--max-rmse", "1"}),
                     {"nan.exr", "pixel (1, 0)", "channel G is nan"});
}

}  // namespace
