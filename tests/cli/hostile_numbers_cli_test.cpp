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

TEST_F(HostileNumbersCliTest, TinySpeedsWidthsAndWavelengthsAreRefused) {
    // 1e-308 as an elongation speed once made every birth time infinite and crashed the shader
    // (RingProfile::lateWood); 1e-30 as a sway wavelength crashed the field. Every speed, width
    // and wavelength has a minimum that makes physical sense, named in the message.
    const std::string rwl = (kSourceDir / "data/rings/nm580.rwl").string();
    const std::string trunk = R"("trunk": {"points": [[0,0,0],[0,0,10]]})";
    const std::string branch = R"("branches": [{"height": 1, "azimuth": 0, "elevation": 30, )";
    struct Case {
        std::string key;
        std::string skeleton, grain;  ///< JSON with @ for the number
        std::string minimum;          ///< how the message names the smallest value allowed
    };
    const std::vector<Case> cases = {
        {"elongation_speed", "{\"elongation_speed\": @, " + trunk + "}", "",
         "at least 0.0001 (m/year"},
        {"ring_widths", "{" + trunk + R"(, "ring_widths": [@, @, @]})", "", "from 1e-06 (1 um)"},
        {"ring_series.mean_width",
         "{" + trunk + R"(, "ring_series": {"file": ")" + rwl +
             R"(", "series": "BCS05B", "mean_width": @}})",
         "", "at least 0.001 (mm"},
        {"branches[0].gamma", "{" + trunk + ", " + branch + R"("gamma": @}]})", "",
         "at least 0.001 (of the trunk"},
        {"branches[0].length", "{" + trunk + ", " + branch + R"("length": @}]})", "",
         "at least 0.001 (m"},
        {"branches[0].death_time", "{" + trunk + ", " + branch + R"("death_time": @}]})", "",
         "at least 0.01 (years"},
        {"radial_speed", "", R"({"radial_speed": @})", "at least 1e-05 (m/year"},
        {"rings.mean_width", "", R"({"rings": {"mean_width": @}})", "at least 1e-06 (m"},
        {"sway.wavelength", "", R"({"sway": {"amplitude": 0.001, "wavelength": @}})",
         "at least 0.01 (m"},
        {"colour.micro.cell_size", "", R"({"colour": {"micro": {"cell_size": @}}})",
         "at least 1e-06 (m"}};
    for (const Case& c : cases)
        for (const char* tiny : {"1e-308", "5e-324", "1e-30"}) {
            SCOPED_TRACE(c.key + " = " + tiny);
            auto fill = [&](std::string text) {
                for (size_t at; (at = text.find('@')) != std::string::npos;)
                    text.replace(at, 1, tiny);
                return text;
            };
            Options options;
            if (!c.skeleton.empty()) {
                std::ofstream(in_ / "s.json") << fill(c.skeleton);
                options["--skeleton"] = (in_ / "s.json").string();
            } else {
                std::ofstream(in_ / "g.json") << fill(c.grain);
                options["--grain"] = (in_ / "g.json").string();
            }
            expectInputError(slice(options), {": " + c.key + ": ", c.minimum});
        }
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
