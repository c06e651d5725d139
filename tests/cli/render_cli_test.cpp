// End-to-end tests of `nenrin render`: outputs and their channels, bitwise determinism across
// thread counts, a reference-image regression with written thresholds, and bad scenes.

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "tests/cli/cli_fixture.h"
#include "tests/scratch_path.h"

namespace {

const fs::path kRegressionScene = kSourceDir / "tests/data/scenes/small-glulam.json";
const fs::path kReference = kSourceDir / "tests/data/ref/small-glulam.exr";

class RenderCliTest : public CliTest {
protected:
    RunResult render(const fs::path& scene, const std::vector<std::string>& extra = {}) {
        std::vector<std::string> args{"render", scene.string(), "-q"};
        args.insert(args.end(), extra.begin(), extra.end());
        return run(args);
    }

    /// A scene file in the input folder; `objects` and `materials` replace the defaults.
    fs::path writeScene(const std::string& name, const std::string& body) {
        fs::path p = in_ / name;
        std::ofstream(p) << body;
        return p;
    }

    std::string woodMaterial(const std::string& extra = "") {
        return fmt::format(R"({{"name": "w", "type": "wood", "skeleton": "{}", "grain": "{}"{}}})",
                           skeletonScene("conifer.json").string(),
                           grainScene("species/norway-spruce.json").string(), extra);
    }

    std::string scene(
        const std::string& materials, const std::string& objects,
        const std::string& camera = R"({"position": [1, 0.5, 1], "look_at": [0, 0, 0], "fov": 40})",
        const std::string& lights = R"([{"type": "sun", "direction": [0, 1, 0]}])") {
        return fmt::format(R"({{"camera": {}, "render": {{"resolution": [16, 12], "spp": 1}},
  "lights": {}, "materials": [{}], "objects": [{}]}})",
                           camera, lights, materials, objects);
    }
};

TEST_F(RenderCliTest, WritesExrWithAovsMetadataAndPngPreview) {
    RunResult r =
        render(kRegressionScene, {"--res", "48x32", "--spp", "2", "-o", (out_ / "r.exr").string(),
                                  "--png", (out_ / "r.png").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("rays/s"), std::string::npos) << r.out;
    auto img = readImage(out_ / "r.exr");
    ASSERT_TRUE(img);
    EXPECT_EQ(img->spec.width, 48);
    EXPECT_EQ(img->spec.height, 32);
    for (const char* c :
         {"R", "G", "B", "A", "albedo.R", "N.X", "Z", "T", "knot", "lamella", "variance",
          "visibility", "occlusion", "diffuse.R", "diffuse.G", "diffuse.B"})
        EXPECT_GE(channelIndex(img->spec, c), 0) << c;
    EXPECT_EQ(img->spec.get_string_attribute("nenrin:scene"), kRegressionScene.string());
    EXPECT_EQ(img->spec.get_string_attribute("nenrin:spp"), "2");
    auto png = readImage(out_ / "r.png");
    ASSERT_TRUE(png);
    EXPECT_EQ(png->spec.nchannels, 3);
    EXPECT_EQ(outputFiles(), (std::vector<std::string>{"r.exr", "r.png"}));
}

TEST_F(RenderCliTest, SameBytesForOneAndTwoThreads) {
    for (const char* threads : {"1", "2"})
        ASSERT_EQ(
            render(kRegressionScene, {"--res", "40x24", "--spp", "3", "--threads", threads, "-o",
                                      (out_ / (std::string(threads) + ".exr")).string()})
                .exitCode,
            0);
    auto a = readImage(out_ / "1.exr"), b = readImage(out_ / "2.exr");
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->pixels, b->pixels);
}

TEST_F(RenderCliTest, AnotherSeedGivesAnotherImageOfTheSameMean) {
    for (const char* seed : {"1", "2"})
        ASSERT_EQ(render(kRegressionScene, {"--res", "40x24", "--spp", "4", "--seed", seed, "-o",
                                            (out_ / (std::string(seed) + ".exr")).string()})
                      .exitCode,
                  0);
    OIIO::ImageBuf a((out_ / "1.exr").string()), b((out_ / "2.exr").string());
    auto cmp = OIIO::ImageBufAlgo::compare(a, b, 0.05f, 1.0f, OIIO::ROI(0, 40, 0, 24, 0, 1, 0, 3));
    EXPECT_GT(cmp.maxerror, 0.0);    // the noise differs...
    EXPECT_LT(cmp.meanerror, 0.05);  // ...the picture does not
}

TEST_F(RenderCliTest, AdaptiveSamplingWritesWhereTheSamplesWentAndTheSameBytesOnAnyThreads) {
    for (const char* threads : {"1", "2"}) {
        RunResult r =
            render(kRegressionScene,
                   {"--res", "40x24", "--spp", "64", "--noise-threshold", "0.1", "--min-spp", "4",
                    "--threads", threads, "-o", (out_ / (std::string(threads) + ".exr")).string()});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_NE(r.out.find("spp on average, 64 at most"), std::string::npos) << r.out;
    }
    auto a = readImage(out_ / "1.exr"), b = readImage(out_ / "2.exr");
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->pixels, b->pixels);
    const int samples = channelIndex(a->spec, "samples");
    ASSERT_GE(samples, 0);
    float lo = 1e9f, hi = 0;
    for (size_t i = samples; i < a->pixels.size(); i += a->spec.nchannels)
        lo = std::min(lo, a->pixels[i]), hi = std::max(hi, a->pixels[i]);
    EXPECT_GE(lo, 4.f);
    EXPECT_LE(hi, 64.f);
    EXPECT_GT(hi, lo);  // the samples went where the noise was
    EXPECT_EQ(a->spec.get_string_attribute("nenrin:noise_threshold"), "0.1");
}

// The visibility AOV against a shadow whose edges are known: a 0.2 m square plate 0.5 m over
// the floor, the sun at 45 degrees over +x, the camera 1 m over the floor looking straight
// down (fov 20: the floor from -0.176 to 0.176 m either way; the plate outside the view). The
// plate's shadow is |x| < 0.1005 (its 1 mm thickness), |z| < 0.1 m: columns 13.76 to 50.24 of
// 64, rows 13.85 to 50.15.
TEST_F(RenderCliTest, VisibilityIsTheShareOfTheSunThatReachesTheFirstHit) {
    const fs::path p = writeScene("shadow.json", R"({
  "camera": {"position": [0, 1, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "fov": 20},
  "render": {"resolution": [64, 64], "spp": 64, "max_depth": 2},
  "lights": [{"type": "sun", "direction": [1, 1, 0]}],
  "materials": [{"name": "grey", "type": "diffuse", "colour": 0.5}],
  "objects": [
    {"type": "box", "size": [4, 0.1, 4], "position": [0, -0.05, 0], "material": "grey"},
    {"type": "box", "size": [0.2, 0.001, 0.2], "position": [0.5, 0.5, 0], "material": "grey"}
  ]})");
    const fs::path out = out_ / "shadow.exr";
    const RunResult r = render(p, {"-o", out.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto img = readImage(out);
    ASSERT_TRUE(img);
    const int v = channelIndex(img->spec, "visibility");
    ASSERT_GE(v, 0);
    const auto at = [&](int x, int y) {
        return img->pixels[(size_t(y) * 64 + x) * img->spec.nchannels + v];
    };
    for (int y = 20; y < 44; ++y) {  // well inside the shadow's extent along z
        for (int x = 0; x < 64; ++x) {
            if (x == 13 || x == 50) {  // three quarters of the pixel lit
                EXPECT_NEAR(at(x, y), 0.76, 0.1) << x << "," << y;
            } else {
                EXPECT_EQ(at(x, y), x > 13 && x < 50 ? 0.f : 1.f) << x << "," << y;
            }
        }
    }
    EXPECT_NEAR(at(32, 13), 0.85, 0.1);  // the shadow's edge along z
    EXPECT_EQ(at(32, 2), 1.f);
}

// The diffuse AOV against the BSDF's own split: a plate under a sun straight above, seen
// from straight above through a 1-degree lens (wo = wi = n at every pixel, to 0.01 degrees),
// nothing else to bounce off. Lambert base/pi under a clear GGX coat (alpha 0.2, F0 0.04):
// diffuse = base/pi (1 - 0.04)^2 E, the coat adds 0.04 D(n) / 4 E with D(n) = 1 / (pi 0.2^2).
TEST_F(RenderCliTest, DiffuseIsThePartOfTheLightTheAlbedoCarries) {
    auto plate = [&](const std::string& material) {
        const fs::path p = writeScene("plate.json", fmt::format(R"({{
  "camera": {{"position": [0, 1, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "fov": 1}},
  "render": {{"resolution": [8, 8], "spp": 4}},
  "lights": [{{"type": "sun", "direction": [0, 1, 0], "irradiance": 3}}],
  "materials": [{}],
  "objects": [{{"type": "box", "size": [1, 0.1, 1], "position": [0, -0.05, 0], "material": "m"}}]
}})",
                                                                material));
        const fs::path out = out_ / "plate.exr";
        const RunResult r = render(p, {"-o", out.string()});
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return readImage(out);
    };
    auto channel = [](const Image& img, const char* name, int pixel) {
        return double(
            img.pixels[size_t(pixel) * img.spec.nchannels + channelIndex(img.spec, name)]);
    };
    constexpr double kPi = 3.14159265358979;
    {  // matte: all of it
        const auto img = plate(R"({"name": "m", "type": "diffuse", "colour": 0.5})");
        ASSERT_TRUE(img);
        for (int i = 0; i < 64; ++i)
            for (const char* c : {"R", "G", "B"})
                EXPECT_EQ(channel(*img, c, i),
                          channel(*img, (std::string("diffuse.") + c).c_str(), i));
        EXPECT_NEAR(channel(*img, "G", 27), 0.5 / kPi * 3, 1e-4);
    }
    {  // a clear coat over it
        const auto img =
            plate(R"({"name": "m", "type": "glossy", "colour": 0.5, "roughness": 0.2})");
        ASSERT_TRUE(img);
        const double base = channel(*img, "albedo.G", 27);
        const double diffuse = base / kPi * 0.96 * 0.96 * 3;
        const double coat = 0.04 / (kPi * 0.2 * 0.2) / 4 * 3;
        for (int i : {18, 27, 36, 45}) {
            EXPECT_NEAR(channel(*img, "diffuse.G", i), diffuse, 1e-3 * diffuse) << i;
            EXPECT_NEAR(channel(*img, "G", i), diffuse + coat, 1e-3 * (diffuse + coat)) << i;
        }
    }
    {  // a metal: none of it
        const auto img =
            plate(R"({"name": "m", "type": "metal", "colour": 0.5, "roughness": 0.2})");
        ASSERT_TRUE(img);
        for (int i = 0; i < 64; ++i) {
            EXPECT_GT(channel(*img, "G", i), 1.0) << i;
            EXPECT_EQ(channel(*img, "diffuse.G", i), 0.0) << i;
        }
    }
}

// The occlusion AOV against its integral: a floor meeting a wall along x = 0, seen from 1 m
// straight above (fov 20: x from -0.076 to 0.276 m). A diffuse floor's first bounce is
// cosine-distributed; a ray leaving a point h from the wall with direction d meets it at
// t = h / -d.x, and counts 1 - t / R within the reach R = 0.15 x the camera ray's length.
TEST_F(RenderCliTest, OcclusionIsHowNearTheFirstBounceFoundGeometry) {
    const fs::path p = writeScene("corner.json", R"({
  "camera": {"position": [0.1, 1, 0], "look_at": [0.1, 0, 0], "up": [0, 0, -1], "fov": 20},
  "render": {"resolution": [64, 64], "spp": 64, "max_depth": 2},
  "lights": [{"type": "sun", "direction": [1, 1, 0.3]}],
  "materials": [{"name": "grey", "type": "diffuse", "colour": 0.5}],
  "objects": [
    {"type": "box", "size": [4, 0.1, 4], "position": [0, -0.05, 0], "material": "grey"},
    {"type": "box", "size": [0.1, 0.4, 4], "position": [-0.05, 0.2, 0], "material": "grey"}
  ]})");
    const fs::path out = out_ / "corner.exr";
    const RunResult r = render(p, {"-o", out.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto img = readImage(out);
    ASSERT_TRUE(img);
    const int o = channelIndex(img->spec, "occlusion");
    ASSERT_GE(o, 0);
    // The integral over the hemisphere (y up), midpoint rule in cos^2(theta) and phi.
    auto expected = [](double h, double reach) {
        constexpr int kRings = 400, kSpokes = 800;
        constexpr double kPi = 3.14159265358979;
        double sum = 0;
        for (int i = 0; i < kRings; ++i) {
            const double cos2 = (i + 0.5) / kRings;  // cosine-weighted: uniform in cos^2
            const double sinTheta = std::sqrt(1 - cos2);
            for (int j = 0; j < kSpokes; ++j) {
                const double dx = sinTheta * std::cos(2 * kPi * (j + 0.5) / kSpokes);
                if (dx < 0) sum += std::max(0.0, 1 - h / -dx / reach);
            }
        }
        return sum / (double(kRings) * kSpokes);
    };
    const double halfWidth = std::tan(10 * 3.14159265358979 / 180);  // m at 1 m
    for (int x = 0; x < 64; ++x) {
        const double h = 0.1 + ((x + 0.5) / 64 * 2 - 1) * halfWidth;  // the column's middle
        if (h < 0.01) continue;  // the wall's top, and its foot's first pixel
        const double reach = 0.15 * std::sqrt(1 + (h - 0.1) * (h - 0.1));
        double mean = 0;
        for (int y = 16; y < 48; ++y)  // rows' own noise averaged
            mean += img->pixels[(size_t(y) * 64 + x) * img->spec.nchannels + o] / 32.0;
        if (h > reach + 0.006) {
            EXPECT_EQ(mean, 0.0) << x;  // nothing within reach, even from the pixel's far edge
        } else {
            // Measured: within 0.003 of the integral from 0.31 at h = 15 mm down to 0.
            EXPECT_NEAR(mean, expected(h, reach), 0.008) << x << " h " << h;
        }
    }
}

TEST_F(RenderCliTest, BadAdaptiveSamplingSettingsAreRejected) {
    const std::string out = (out_ / "x.exr").string();
    RunResult r = render(kRegressionScene, {"--noise-threshold", "2", "-o", out});
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find("--noise-threshold"), std::string::npos) << r.err;
    expectInputError(render(kRegressionScene, {"--noise-threshold", "0.05", "--spp", "8",
                                               "--min-spp", "16", "-o", out}),
                     {"--min-spp", "16"});
    fs::path p = writeScene("s.json", R"({"camera": {"position": [1, 1, 1], "look_at": [0, 0, 0]},
          "render": {"noise_threshold": -0.1},
          "materials": [{"name": "m", "type": "diffuse"}],
          "objects": [{"type": "box", "size": [1, 1, 1], "material": "m"}]})");
    expectInputError(render(p, {"-o", out}), {"render.noise_threshold"});
    EXPECT_TRUE(outputFiles().empty());
}

// The regression reference: tests/data/ref/small-glulam.exr, made by
//   nenrin render tests/data/scenes/small-glulam.json -o tests/data/ref/small-glulam.exr
// Thresholds: the same build reproduces it bitwise; another compiler or libm may move a few
// samples (a changed path choice is one noisy sample of 8), so allow at most 1 % of values to
// differ by more than 0.02 and a mean error of 0.004. Raise them only with a reason.
TEST_F(RenderCliTest, MatchesTheReferenceImage) {
    ASSERT_TRUE(fs::exists(kReference)) << kReference;
    fs::path out = out_ / "small-glulam.exr";
    RunResult r = render(kRegressionScene, {"-o", out.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    OIIO::ImageBuf image(out.string()), reference(kReference.string());
    auto cmp = OIIO::ImageBufAlgo::compare(image, reference, 0.02f, 1.0f,
                                           OIIO::ROI(0, 96, 0, 64, 0, 1, 0, 3));
    double values = 96.0 * 64 * 3;
    // The test folder is removed afterwards: keep the candidate where the message says.
    const fs::path candidate = nenrin::scratchPath("small-glulam-candidate.exr");
    if (cmp.nfail / values > 0.01 || cmp.meanerror > 0.004)
        fs::copy_file(out, candidate, fs::copy_options::overwrite_existing);
    EXPECT_LE(cmp.nfail / values, 0.01)
        << "max error " << cmp.maxerror << " at " << cmp.maxx << "," << cmp.maxy
        << "; to accept a new reference, copy " << candidate << " to " << kReference;
    EXPECT_LE(cmp.meanerror, 0.004)
        << "to accept a new reference, copy " << candidate << " to " << kReference;
}

TEST_F(RenderCliTest, MalformedSceneNamesLineAndColumn) {
    fs::path p = writeScene("bad.json", "{\n  \"camera\": {\"position\": [0, 1, 2],,}\n}");
    expectInputError(render(p, {"-o", (out_ / "x.exr").string()}), {p.string(), "line 2"});
}

TEST_F(RenderCliTest, MissingSceneFileIsReported) {
    expectInputError(render(in_ / "nope.json", {"-o", (out_ / "x.exr").string()}), {"nope.json"});
}

TEST_F(RenderCliTest, UnknownCameraKeyIsRejected) {
    fs::path p = writeScene(
        "s.json", scene(woodMaterial(), R"({"type": "box", "size": [1, 1, 1], "material": "w"})",
                        R"({"position": [1, 1, 1], "look_at": [0, 0, 0], "fox": 40})"));
    expectInputError(render(p, {"-o", (out_ / "x.exr").string()}), {"camera.fox", "unknown key"});
}

TEST_F(RenderCliTest, NegativeIrradianceIsRejected) {
    fs::path p = writeScene(
        "s.json", scene(woodMaterial(), R"({"type": "box", "size": [1, 1, 1], "material": "w"})",
                        R"({"position": [1, 1, 1], "look_at": [0, 0, 0]})",
                        R"([{"type": "sun", "direction": [0, 1, 0], "irradiance": -2}])"));
    expectInputError(render(p, {"-o", (out_ / "x.exr").string()}),
                     {"lights[0].irradiance", ">= 0"});
}

TEST_F(RenderCliTest, UnknownMaterialIsRejected) {
    fs::path p = writeScene(
        "s.json",
        scene(woodMaterial(), R"({"type": "box", "size": [1, 1, 1], "material": "oak"})"));
    expectInputError(render(p, {"-o", (out_ / "x.exr").string()}),
                     {"objects[0].material", "no material named \"oak\""});
}

TEST_F(RenderCliTest, UnknownFinishIsRejected) {
    fs::path p =
        writeScene("s.json", scene(woodMaterial(R"(, "finish": "waxed")"),
                                   R"({"type": "box", "size": [1, 1, 1], "material": "w"})"));
    expectInputError(render(p, {"-o", (out_ / "x.exr").string()}),
                     {"materials[0].finish", "matte, oiled, varnished, bare"});
}

TEST_F(RenderCliTest, MissingSkeletonOfAWoodMaterialIsReported) {
    fs::path p = writeScene(
        "s.json", scene(R"({"name": "w", "type": "wood", "skeleton": "no-such-tree.json"})",
                        R"({"type": "box", "size": [1, 1, 1], "material": "w"})"));
    expectInputError(render(p, {"-o", (out_ / "x.exr").string()}), {"no-such-tree.json"});
}

TEST_F(RenderCliTest, BoardTooWideForTheLogIsReported) {
    fs::path p = writeScene(
        "s.json", scene(woodMaterial(), R"({"type": "glulam", "width": 1.5, "material": "w"})"));
    expectInputError(render(p, {"-o", (out_ / "x.exr").string()}),
                     {"objects[0].cut", "does not fit in the log"});
}

TEST_F(RenderCliTest, EvenCltLayerCountIsRejected) {
    fs::path p = writeScene(
        "s.json", scene(woodMaterial(), R"({"type": "clt", "layers": 4, "material": "w"})"));
    expectInputError(render(p, {"-o", (out_ / "x.exr").string()}), {"objects[0].layers", "odd"});
}

TEST_F(RenderCliTest, LaminatedProductOfPaintIsRejected) {
    fs::path p = writeScene("s.json", scene(R"({"name": "w", "type": "diffuse"})",
                                            R"({"type": "table_top", "material": "w"})"));
    expectInputError(render(p, {"-o", (out_ / "x.exr").string()}),
                     {"objects[0].material", "wood material"});
}

TEST_F(RenderCliTest, MissingEnvironmentMapIsReported) {
    fs::path p = writeScene(
        "s.json", scene(woodMaterial(), R"({"type": "box", "size": [1, 1, 1], "material": "w"})",
                        R"({"position": [1, 1, 1], "look_at": [0, 0, 0]})",
                        R"([{"type": "environment", "map": "sky-missing.exr"}])"));
    expectInputError(render(p, {"-o", (out_ / "x.exr").string()}), {"sky-missing.exr"});
}

TEST_F(RenderCliTest, AbsurdResolutionIsRejectedBeforeWork) {
    expectInputError(
        render(kRegressionScene, {"--res", "100000x100000", "-o", (out_ / "x.exr").string()}),
        {"--res"});
}

TEST_F(RenderCliTest, ResolutionInTheSceneIsChecked) {
    fs::path p = writeScene("s.json",
                            R"({"camera": {"position": [1, 1, 1], "look_at": [0, 0, 0]},
            "render": {"resolution": [0, 10]}, "materials": [{"name": "m", "type": "diffuse"}],
            "objects": [{"type": "box", "size": [1, 1, 1], "material": "m"}]})");
    expectInputError(render(p, {"-o", (out_ / "x.exr").string()}), {"render.resolution"});
}

TEST_F(RenderCliTest, NonExrOutputIsRejected) {
    expectInputError(render(kRegressionScene, {"-o", (out_ / "x.png").string()}), {".exr"});
}

TEST_F(RenderCliTest, CameraLookingAtItselfIsRejected) {
    fs::path p = writeScene(
        "s.json", scene(woodMaterial(), R"({"type": "box", "size": [1, 1, 1], "material": "w"})",
                        R"({"position": [1, 1, 1], "look_at": [1, 1, 1]})"));
    expectInputError(render(p, {"-o", (out_ / "x.exr").string()}), {"camera.look_at"});
}

}  // namespace
