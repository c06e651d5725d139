// End-to-end tests of `nenrin stats`: the figures of a bake in text and JSON (the keys of the
// team's photo-stats script), --against and --rings, and one clear line for every bad input.

#include <nlohmann/json.hpp>

#include "tests/cli/cli_fixture.h"

namespace {

class StatsCliTest : public CliTest {
protected:
    /// Writes a float image with named channels (values channel-interleaved).
    fs::path writeImage(const std::string& name, int w, int h,
                        const std::vector<std::string>& channels, std::vector<float> pixels) {
        const fs::path path = in_ / name;
        OIIO::ImageSpec spec(w, h, int(channels.size()), OIIO::TypeDesc::FLOAT);
        spec.channelnames = channels;
        auto out = OIIO::ImageOutput::create(path.string());
        EXPECT_TRUE(out && out->open(path.string(), spec) &&
                    out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
        if (out) out->close();
        return path;
    }

    /// A w x h image whose channels all hold `value`.
    fs::path flatImage(const std::string& name, int w, int h,
                       const std::vector<std::string>& channels, float value = 0.5f) {
        return writeImage(name, w, h, channels,
                          std::vector<float>(size_t(w) * h * channels.size(), value));
    }

    /// A 64 x 64 cross-section of the straight trunk, its rings in view, into in/slice.exr.
    fs::path bakeSlice() {
        const fs::path slice = in_ / "slice.exr";
        RunResult r = run(bakeArgs("slice",
                                   {{"--skeleton", skeletonScene("straight-trunk.json").string()},
                                    {"--plane", "cross"},
                                    {"--at", "1"},
                                    {"--size", "0.1x0.1m"},
                                    {"--res", "64x64"},
                                    {"-o", slice.string()}},
                                   {}));
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return slice;
    }
};

TEST_F(StatsCliTest, HelpExplainsEveryFigure) {
    RunResult r = run({"stats", "--help"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* figure : {"L*a*b*", "std_L", "fine ", "mid ", "dir_spread", "fine_aniso",
                               "--against", "dE", "--rings", "within 15 deg", "--json", "256"})
        EXPECT_NE(r.out.find(figure), std::string::npos) << figure << "\n" << r.out;
}

TEST_F(StatsCliTest, FiguresOfABakeInTextAndJson) {
    const fs::path slice = bakeSlice();
    RunResult text = run({"stats", slice.string()});
    ASSERT_EQ(text.exitCode, 0) << text.err;
    EXPECT_EQ(text.out.rfind(slice.string() + ": L*a*b* ", 0), 0u) << text.out;
    for (const char* piece : {"std_L", "fine", "mid", "dir_spread", "deg  fine_aniso"})
        EXPECT_NE(text.out.find(piece), std::string::npos) << text.out;

    RunResult json = run({"stats", slice.string(), "--json"});
    ASSERT_EQ(json.exitCode, 0) << json.err;
    const auto j = nlohmann::ordered_json::parse(json.out);
    std::vector<std::string> keys;
    for (const auto& item : j.items()) keys.push_back(item.key());
    EXPECT_EQ(keys, (std::vector<std::string>{"image", "lab", "std_L", "fine", "mid", "dir_spread",
                                              "fine_aniso"}));
    EXPECT_EQ(j["image"], slice.string());
    EXPECT_EQ(j["lab"].size(), 3u);
    EXPECT_GT(j["mid"].get<double>(), 0);  // rings
}

TEST_F(StatsCliTest, AgainstItselfEveryRatioIsOne) {
    const fs::path slice = bakeSlice();
    RunResult r = run({"stats", "--json", "--against", slice.string(), slice.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::istringstream lines(r.out);
    std::string photoLine, imageLine, extra;
    ASSERT_TRUE(std::getline(lines, photoLine) && std::getline(lines, imageLine)) << r.out;
    EXPECT_FALSE(std::getline(lines, extra));
    EXPECT_FALSE(nlohmann::json::parse(photoLine).contains("vs"));
    const auto vs = nlohmann::json::parse(imageLine)["vs"];
    EXPECT_EQ(vs, (nlohmann::json{{"dE_ab", 0.0},
                                  {"fine_ratio", 1.0},
                                  {"mid_ratio", 1.0},
                                  {"dir_spread_diff", 0.0},
                                  {"fine_aniso_ratio", 1.0}}));
    RunResult text = run({"stats", "--against", slice.string(), slice.string()});
    EXPECT_NE(text.out.find("| vs photo: dE 0.0, fine x1.00, mid x1.00, dir_spread +0.0 deg, "
                            "fine_aniso x1.00"),
              std::string::npos)
        << text.out;
}

TEST_F(StatsCliTest, RingsOfABakeAgreeWithItsOwnGrowthTime) {
    const fs::path slice = bakeSlice();
    RunResult r = run({"stats", "--rings", slice.string(), slice.string(), "--json"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto j = nlohmann::ordered_json::parse(r.out);
    std::vector<std::string> keys;
    for (const auto& item : j.items()) keys.push_back(item.key());
    EXPECT_EQ(keys, (std::vector<std::string>{"photo", "field", "median_deg", "within_15deg"}));
    EXPECT_LT(j["median_deg"].get<double>(), 15);
    EXPECT_GT(j["within_15deg"].get<double>(), 0.5);
    RunResult text = run({"stats", "--rings", slice.string(), slice.string()});
    EXPECT_NE(text.out.find(" vs " + slice.string() + ": ring normals median "), std::string::npos)
        << text.out;
    EXPECT_NE(text.out.find("% within 15 deg"), std::string::npos) << text.out;
}

TEST_F(StatsCliTest, BadImagesAreNamedWithWhatWasExpected) {
    const fs::path text = in_ / "notes.png";
    std::ofstream(text) << "not an image\n";
    expectInputError(run({"stats", (in_ / "missing.png").string()}),
                     {"missing.png", "no such file"});
    expectInputError(run({"stats", text.string()}), {"notes.png", "cannot read"});
    std::vector<float> pixels(32 * 32 * 3, 0.5f);
    pixels[4] = std::nanf("");  // pixel (1, 0), G
    expectInputError(run({"stats", writeImage("nan.exr", 32, 32, {"R", "G", "B"}, pixels)}),
                     {"nan.exr", "pixel (1, 0)", "channel G is nan", "finite"});
    expectInputError(run({"stats", flatImage("t-only.exr", 32, 32, {"T"}).string()}),
                     {"t-only.exr", "channels T", "expected R, G, B"});
    expectInputError(run({"stats", flatImage("one.exr", 1, 1, {"R", "G", "B"}).string()}),
                     {"one.exr", "1x1 pixels", "expected at least 16x16"});
    expectInputError(run({"stats", flatImage("flat.exr", 32, 32, {"R", "G", "B"}).string(),
                          "--against", flatImage("flat-photo.exr", 32, 32, {"R", "G", "B"})}),
                     {"flat-photo.exr", "expected a photograph with texture"});
}

TEST_F(StatsCliTest, RingsNeedAPhotoAndAGrowthTimeOnOneGrid) {
    const fs::path slice = bakeSlice();
    const std::string photo = flatImage("photo.exr", 64, 64, {"R", "G", "B"}).string();
    expectInputError(run({"stats", "--rings", photo, photo}),
                     {"photo.exr", "no channel T", "channels: R, G, B"});
    expectInputError(
        run({"stats", "--rings", flatImage("photo48.exr", 48, 48, {"R", "G", "B"}).string(),
             slice.string()}),
        {"slice.exr", "64x64 pixels, but", "photo48.exr is 48x48", "pixel grid"});
    expectInputError(run({"stats", "--rings", photo}), {"--rings", "PHOTO FIELD.exr", "found 1"});
    expectInputError(run({"stats", "--rings", photo, slice.string(), "--against", photo}),
                     {"--rings", "--against"});
    std::vector<float> t(64 * 64, 1.f);
    t[70] = INFINITY;
    expectInputError(run({"stats", "--rings", slice.string(),
                          writeImage("inf-t.exr", 64, 64, {"T"}, t).string()}),
                     {"inf-t.exr", "pixel (6, 1)", "channel T is inf"});
}

}  // namespace
