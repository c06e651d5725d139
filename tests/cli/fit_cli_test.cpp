// nenrin fit (fit/, docs/fit.md) end to end: the Mokume hinoki cube fitted with a face left
// out, that face baked through the fit with `nenrin bake slice` and its rings measured against
// the photograph with `nenrin stats --rings`, as the issue judges a fit; bad samples refused.

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/cli/cli_fixture.h"

namespace nenrin {
namespace {

const fs::path kMokume = kSourceDir / "../shared/data/mokume";

class FitCliTest : public CliTest {
protected:
    /// A sample file in the input folder: a 5 cm cube's end faces and two sides (named A to
    /// D), `image` for every face.
    fs::path sampleWith(const std::string& image) {
        nlohmann::json faces = nlohmann::json::array();
        auto face = [&](const char* name, nlohmann::json origin, nlohmann::json right,
                        nlohmann::json up) {
            faces.push_back({{"name", name},
                             {"image", image},
                             {"origin", origin},
                             {"right", right},
                             {"up", up}});
        };
        face("A", {-0.025, -0.025, 0.025}, {0.05, 0, 0}, {0, 0.05, 0});
        face("B", {-0.025, 0.025, 0.025}, {0.05, 0, 0}, {0, 0, -0.05});
        face("C", {-0.025, -0.025, -0.025}, {0, 0, 0.05}, {0, 0.05, 0});
        face("D", {-0.025, -0.025, -0.025}, {0.05, 0, 0}, {0, 0, 0.05});
        const fs::path p = in_ / "sample.json";
        std::ofstream(p) << nlohmann::json{{"size", {0.05, 0.05, 0.05}}, {"faces", faces}}.dump(1);
        return p;
    }
    /// A grey PNG in the input folder: flat, or noise.
    fs::path greyImage(const std::string& name, bool noise, int width = 256) {
        std::vector<unsigned char> pixels(size_t(width) * 256);
        unsigned state = 12345;
        for (auto& p : pixels) {
            state = state * 1103515245u + 12345u;
            p = noise ? static_cast<unsigned char>(state >> 24) : 128;
        }
        const fs::path p = in_ / name;
        auto out = OIIO::ImageOutput::create(p.string());
        out->open(p.string(), OIIO::ImageSpec(width, 256, 1, OIIO::TypeDesc::UINT8));
        out->write_image(OIIO::TypeDesc::UINT8, pixels.data());
        out->close();
        return p;
    }
};

TEST_F(FitCliTest, AFaceLeftOutIsBakedWithRingsAsInItsPhotograph) {
    if (!fs::exists(kMokume / "H11/sample.json"))
        GTEST_SKIP() << "no Mokume photographs at " << kMokume << " (../shared/data/mokume)";
    const std::string sample = (kMokume / "H11/sample.json").string();
    auto r = run({"fit", sample, "-o", "fit", "--leave-out", "E", "--threads", "2", "--grain",
                  grainScene("species/hinoki.json").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* file : {"skeleton.json", "grain.json", "fit.json", "report.png"})
        EXPECT_TRUE(fs::exists(out_ / "fit" / file)) << file;
    const nlohmann::json report = nlohmann::json::parse(readText(out_ / "fit/fit.json"));
    ASSERT_EQ(report["faces"].size(), 6u);
    EXPECT_TRUE(report["faces"][4]["held_out"].get<bool>());
    EXPECT_GE(report["rings"]["count"].get<int>(), 5);
    // The pith of H11 lies outside the cube, a few centimetres off (its end faces show arcs).
    const double distance = report["pith"]["distance"].get<double>();
    EXPECT_GT(distance, 0.03);
    EXPECT_LT(distance, 0.2);
    auto image = OIIO::ImageInput::open((out_ / "fit/report.png").string());
    ASSERT_TRUE(image);
    EXPECT_EQ(image->spec().width, 6 * 256 + 7 * 4);
    EXPECT_EQ(image->spec().height, 2 * 256 + 3 * 4);

    // Face E (x = +25 mm, quarter-sawn), never seen by the fit: baked through it, its rings
    // against the photograph's. Measured 2.9 degrees when written; the bound for any
    // held-out face is 20.
    auto b = run({"bake", "slice", "--skeleton", (out_ / "fit/skeleton.json").string(), "--grain",
                  (out_ / "fit/grain.json").string(), "--origin", "0.025,-0.025,0.025", "--right",
                  "0,0,-0.05", "--up", "0,0.05,0", "--res", "256x256", "-o", "E.exr"});
    ASSERT_EQ(b.exitCode, 0) << b.err;
    auto s = run({"stats", "--rings", (kMokume / "H11/E_col.png").string(),
                  (out_ / "E.exr").string(), "--json"});
    ASSERT_EQ(s.exitCode, 0) << s.err;
    const nlohmann::json rings = nlohmann::json::parse(s.out);
    EXPECT_LT(rings["median_deg"].get<double>(), 20) << s.out;
    // fit.json says the same of the face.
    EXPECT_NEAR(report["faces"][4]["ring_median_deg"].get<double>(),
                rings["median_deg"].get<double>(), 0.5);
}

TEST_F(FitCliTest, RefusesSamplesThatShowNoWood) {
    const fs::path flat = sampleWith(greyImage("flat.png", false).string());
    expectInputError(run({"fit", flat.string(), "-o", "fit"}),
                     {"sample.json", "no ring structure"});
    const fs::path noise = sampleWith(greyImage("noise.png", true).string());
    auto r = run({"fit", noise.string(), "-o", "fit"});
    expectInputError(r, {"sample.json"});
    const fs::path wide = sampleWith(greyImage("wide.png", true, 512).string());
    expectInputError(run({"fit", wide.string(), "-o", "fit"}), {"wide.png", "512 x 256"});
    expectInputError(run({"fit", flat.string(), "-o", "fit", "--leave-out", "Q"}),
                     {"--leave-out", "Q"});
    expectInputError(run({"fit", flat.string(), "-o", "fit", "--leave-out", "A", "--leave-out", "B",
                          "--leave-out", "C", "--leave-out", "D"}),
                     {"--leave-out", "nothing to fit"});
    expectInputError(run({"fit", (in_ / "missing.json").string(), "-o", "fit"}), {"missing.json"});
}

}  // namespace
}  // namespace nenrin
