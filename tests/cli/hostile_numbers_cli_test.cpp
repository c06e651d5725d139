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

}  // namespace
