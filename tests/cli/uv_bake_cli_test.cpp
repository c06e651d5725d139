// End-to-end tests of `nenrin bake uv`: the maps and the textured mesh it writes, a render of
// the baked cube against nenrin's direct solid-texture render, grain continuity across the
// seams, padding, deterministic bytes, and bad input.

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "tests/cli/cli_fixture.h"

namespace {

const fs::path kCubeScene = kSourceDir / "tests/data/scenes/uv-cube.json";

class UvBakeCliTest : public CliTest {
protected:
    /// A scene holding one wood mesh object "tri" made of `mesh`.
    fs::path meshScene(const fs::path& mesh) {
        fs::path scene = in_ / "s.json";
        std::ofstream(scene) << fmt::format(
            R"({{"camera": {{"position": [0, 0, 2], "look_at": [0, 0, 0]}},
  "materials": [{{"name": "w", "type": "wood", "skeleton": "{}"}}],
  "objects": [{{"name": "tri", "type": "mesh", "file": "{}", "material": "w"}}]}})",
            skeletonScene("straight-trunk.json").string(), mesh.string());
        return scene;
    }

    RunResult bake(const fs::path& folder, const std::vector<std::string>& extra = {}) {
        std::vector<std::string> args{"bake",     "uv",   "--scene", kCubeScene.string(),
                                      "--object", "cube", "-o",      folder.string(),
                                      "-q"};
        args.insert(args.end(), extra.begin(), extra.end());
        return run(args);
    }
};

TEST_F(UvBakeCliTest, WritesMapsMeshAndMaterial) {
    RunResult r = bake(out_, {"--res", "128"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(outputFiles(),
              (std::vector<std::string>{"basecolor.exr", "coverage.exr", "cube.mtl", "cube.obj",
                                        "fibre.exr", "growth.exr", "normal.exr", "roughness.exr",
                                        "texture-set.json"}));
    auto base = readImage(out_ / "basecolor.exr");
    auto coverage = readImage(out_ / "coverage.exr");
    ASSERT_TRUE(base && coverage);
    EXPECT_EQ(base->spec.width, 128);
    // Opaque: no alpha channel a tool could un-premultiply; coverage is its own mask.
    EXPECT_EQ(base->spec.nchannels, 3);
    EXPECT_EQ(coverage->spec.nchannels, 1);
    // Data maps say so (colorInteropID "data"); the base colour is scene-linear colour.
    EXPECT_EQ(coverage->spec.get_string_attribute("colorInteropID"), "data");
    EXPECT_EQ(base->spec.get_string_attribute("colorInteropID"), "");
    EXPECT_EQ(base->spec.get_string_attribute("oiio:ColorSpace"), "Linear");
    std::string mtl = readText(out_ / "cube.mtl");
    for (const char* key : {"map_Kd basecolor.exr", "map_Pr roughness.exr", "norm normal.exr",
                            "Ks 0.5 0.5 0.5", "Pc 0.6000", "Pcr 0.6708", "Pr 0.4690"})
        EXPECT_NE(mtl.find(key), std::string::npos) << key << " in\n" << mtl;
    // map_Bump would be read as a height map; Ks 0 would switch the coat off.
    EXPECT_EQ(mtl.find("map_Bump"), std::string::npos) << mtl;
    EXPECT_EQ(mtl.find("Ks 0 "), std::string::npos) << mtl;
    EXPECT_NE(readText(out_ / "cube.obj").find("mtllib cube.mtl"), std::string::npos);
    auto description = nlohmann::json::parse(readText(out_ / "texture-set.json"));
    EXPECT_EQ(description["format"], "nenrin texture set");
    EXPECT_NEAR(description["finish"]["coat_roughness"].get<double>(), std::sqrt(0.45), 1e-9);
    // Perceptual roughness: the matte fibre lobe's width 0.22 rad is its GGX alpha.
    auto roughness = readImage(out_ / "roughness.exr");
    ASSERT_TRUE(roughness);
    for (float v : roughness->pixels) ASSERT_NEAR(v, std::sqrt(0.22), 1e-6);
    // A flat chart interior with the matte finish's faint relief: the normal map is
    // (0.5, 0.5, ~1).
    auto normal = readImage(out_ / "normal.exr");
    ASSERT_TRUE(normal);
    double zMean = 0, count = 0;
    for (size_t i = 0; i < coverage->pixels.size(); ++i) {
        if (coverage->pixels[i] < 1) continue;
        zMean += normal->pixels[3 * i + 2];
        count += 1;
    }
    EXPECT_GT(zMean / count, 0.98);
}

TEST_F(UvBakeCliTest, PaddingFillsAGutterAndTheRestIsNeutral) {
    ASSERT_EQ(bake(out_, {"--res", "256", "--padding", "4"}).exitCode, 0);
    auto base = readImage(out_ / "basecolor.exr");
    auto coverage = readImage(out_ / "coverage.exr");
    auto normal = readImage(out_ / "normal.exr");
    auto fibre = readImage(out_ / "fibre.exr");
    ASSERT_TRUE(base && coverage && normal && fibre);
    // Coverage marks the charts; RGB must be wood up to 4 texels outside them, and past the
    // gutter the mean wood colour, a flat normal and a fibre along +u: no zero vectors.
    size_t padded = 0, empty = 0;
    const int w = 256;
    double mean[3] = {0, 0, 0}, covered = 0;
    for (size_t i = 0; i < size_t(w) * w; ++i)
        if (coverage->pixels[i] > 0) {
            for (int c = 0; c < 3; ++c) mean[c] += base->pixels[3 * i + c];
            covered += 1;
        }
    for (int y = 0; y < w; ++y)
        for (int x = 0; x < w; ++x) {
            size_t i = size_t(y) * w + x;
            if (coverage->pixels[i] > 0) continue;
            bool nearChart = false;
            for (int dy = -4; dy <= 4 && !nearChart; ++dy)
                for (int dx = -4; dx <= 4 && !nearChart; ++dx) {
                    int xx = x + dx, yy = y + dy;
                    if (xx >= 0 && yy >= 0 && xx < w && yy < w &&
                        coverage->pixels[size_t(yy) * w + xx] > 0)
                        nearChart = true;
                }
            if (nearChart) {
                EXPECT_GT(base->pixels[3 * i], 0.f) << x << "," << y;
                ++padded;
                continue;
            }
            ++empty;
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(base->pixels[3 * i + c], mean[c] / covered, 1e-5) << x << "," << y;
            ASSERT_EQ(normal->pixels[3 * i], 0.5f);
            ASSERT_EQ(normal->pixels[3 * i + 1], 0.5f);
            ASSERT_EQ(normal->pixels[3 * i + 2], 1.f);
            ASSERT_EQ(fibre->pixels[3 * i], 1.f);
            ASSERT_EQ(fibre->pixels[3 * i + 1], 0.5f);
        }
    EXPECT_GT(padded, 100u);
    EXPECT_GT(empty, 0u);
}

TEST_F(UvBakeCliTest, ReliefShowsWhereTheWoodHasItAndIsFlatWhereItHasNone) {
    // The tilt of the baked normals: a brushed finish leaves the late wood 0.15 mm proud, and
    // at 0.8 mm texels its edges tilt by degrees; bare wood has no relief at all.
    auto tilts = [&](const std::string& finish) {
        std::string text = readText(kCubeScene);
        size_t at = text.find(R"("finish": "matte")");
        EXPECT_NE(at, std::string::npos);
        text.replace(at, 17, "\"finish\": \"" + finish + "\"");
        for (const char* rel : {"../../../scenes/", "../grain/", "../meshes/"}) {
            size_t p = text.find(rel);
            EXPECT_NE(p, std::string::npos) << rel;
            text.replace(p, std::string(rel).size(),
                         (kSourceDir / "tests/data/scenes" / rel).lexically_normal().string());
        }
        fs::path scene = in_ / (finish + ".json"), folder = out_ / finish;
        std::ofstream(scene) << text;
        fs::create_directory(folder);
        RunResult r = run({"bake", "uv", "--scene", scene.string(), "--object", "cube", "--res",
                           "256", "-o", folder.string(), "-q"});
        EXPECT_EQ(r.exitCode, 0) << r.err;
        auto normal = readImage(folder / "normal.exr");
        auto coverage = readImage(folder / "coverage.exr");
        std::vector<double> t;
        for (size_t i = 0; normal && coverage && i < coverage->pixels.size(); ++i)
            if (coverage->pixels[i] > 0) {
                double x = 2 * normal->pixels[3 * i] - 1, y = 2 * normal->pixels[3 * i + 1] - 1;
                t.push_back(std::atan(std::hypot(x, y) / (2 * normal->pixels[3 * i + 2] - 1)) *
                            180 / M_PI);
            }
        std::sort(t.begin(), t.end());
        return t;
    };
    std::vector<double> brushed = tilts("brushed"), bare = tilts("bare");
    ASSERT_FALSE(brushed.empty());
    ASSERT_FALSE(bare.empty());
    double p90 = brushed[brushed.size() * 9 / 10], p99 = brushed[brushed.size() * 99 / 100];
    std::printf("brushed: tilt p90 %.2f, p99 %.2f degrees; bare: max %.4f degrees\n", p90, p99,
                bare.back());
    EXPECT_GT(p90, 1.0);  // a strength-1 normal map shows it in a highlight
    EXPECT_LT(p99, 45.0);
    EXPECT_LT(bare.back(), 0.01);  // flat (8-bit-free float EXR: exactly (0, 0, 1) up to float)
}

TEST_F(UvBakeCliTest, GltfFilesComeWithTheFlagAndCarryTheMaps) {
    ASSERT_EQ(bake(out_, {"--res", "64"}).exitCode, 0);
    EXPECT_FALSE(fs::exists(out_ / "cube.gltf"));
    fs::path g = out_ / "g";
    fs::create_directory(g);
    ASSERT_EQ(bake(g, {"--res", "64", "--gltf"}).exitCode, 0);
    for (const char* f : {"cube.gltf", "cube.bin", "cube.glb", "basecolor.png",
                          "metallic-roughness.png", "normal.png", "anisotropy.png"})
        EXPECT_TRUE(fs::exists(g / f)) << f;
    // The PNGs are the EXR maps in glTF's encodings: base colour sRGB, roughness in G,
    // the normal map as is.
    auto exrBase = readImage(g / "basecolor.exr"), pngBase = readImage(g / "basecolor.png");
    auto exrRough = readImage(g / "roughness.exr"), mr = readImage(g / "metallic-roughness.png");
    auto exrNormal = readImage(g / "normal.exr"), pngNormal = readImage(g / "normal.png");
    ASSERT_TRUE(exrBase && pngBase && exrRough && mr && exrNormal && pngNormal);
    for (size_t i = 0; i < exrRough->pixels.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            double linear = std::clamp<double>(exrBase->pixels[3 * i + c], 0, 1);
            double srgb =
                linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
            ASSERT_NEAR(pngBase->pixels[3 * i + c], srgb, 0.5 / 255 + 1e-6) << i;
            ASSERT_NEAR(pngNormal->pixels[3 * i + c], exrNormal->pixels[3 * i + c],
                        0.5 / 255 + 1e-6);
        }
        ASSERT_NEAR(mr->pixels[3 * i + 1], exrRough->pixels[i], 0.5 / 255 + 1e-6);
        ASSERT_EQ(mr->pixels[3 * i + 2], 0.f);  // metallic
    }
    auto gltf = nlohmann::json::parse(readText(g / "cube.gltf"));
    EXPECT_EQ(gltf["buffers"][0]["uri"], "cube.bin");
    EXPECT_EQ(gltf["buffers"][0]["byteLength"].get<size_t>(), fs::file_size(g / "cube.bin"));
    const auto& material = gltf["materials"][0];
    EXPECT_NEAR(
        material["extensions"]["KHR_materials_clearcoat"]["clearcoatRoughnessFactor"].get<double>(),
        std::sqrt(0.45), 1e-9);
    EXPECT_GT(
        material["extensions"]["KHR_materials_anisotropy"]["anisotropyStrength"].get<double>(),
        0.5);
}

TEST_F(UvBakeCliTest, AGlbMeshBakesLikeTheObjItCameFrom) {
    fs::path first = out_ / "first", second = out_ / "second";
    fs::create_directory(first);
    fs::create_directory(second);
    ASSERT_EQ(bake(first, {"--res", "128", "--gltf"}).exitCode, 0);
    // The written .glb (the 0.1 m cube, already scaled) as the input mesh of the same scene.
    std::string text = readText(kCubeScene);
    const std::string from = R"("file": "../meshes/uv-cube.obj", "scale": 0.5)";
    size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos);
    text.replace(at, from.size(), "\"file\": \"" + (first / "cube.glb").string() + "\"");
    for (const char* rel : {"../../../scenes/", "../grain/"}) {
        size_t p = text.find(rel);
        ASSERT_NE(p, std::string::npos) << rel;
        text.replace(p, std::string(rel).size(),
                     (kSourceDir / "tests/data/scenes" / rel).lexically_normal().string());
    }
    fs::path scene = in_ / "from-glb.json";
    std::ofstream(scene) << text;
    RunResult r = run({"bake", "uv", "--scene", scene.string(), "--object", "cube", "--res", "128",
                       "-o", second.string(), "-q"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto a = readImage(first / "growth.exr"), b = readImage(second / "growth.exr");
    auto ca = readImage(first / "coverage.exr"), cb = readImage(second / "coverage.exr");
    ASSERT_TRUE(a && b && ca && cb);
    EXPECT_EQ(ca->pixels, cb->pixels);  // the same uv layout
    double worst = 0;
    for (size_t i = 0; i < ca->pixels.size(); ++i)
        if (ca->pixels[i] > 0)
            worst = std::max(worst, double(std::abs(a->pixels[2 * i] - b->pixels[2 * i])));
    EXPECT_LT(worst, 1e-3) << "years";  // float32 positions in both files
}

TEST_F(UvBakeCliTest, SameBytesForOneAndTwoThreads) {
    fs::path a = out_ / "a", b = out_ / "b";
    fs::create_directory(a);
    fs::create_directory(b);
    ASSERT_EQ(bake(a, {"--res", "96", "--threads", "1"}).exitCode, 0);
    ASSERT_EQ(bake(b, {"--res", "96", "--threads", "2"}).exitCode, 0);
    for (const char* f : {"basecolor.exr", "coverage.exr", "roughness.exr", "normal.exr",
                          "fibre.exr", "growth.exr"})
        EXPECT_EQ(readBytes(a / f), readBytes(b / f)) << f;
}

TEST_F(UvBakeCliTest, GrainIsContinuousAcrossTheSeams) {
    // The cube's edge between the +x face (chart 0) and the +y face (chart 2) appears in two
    // charts; the growth time baked just inside each must agree within what the texels'
    // distance on the surface (up to ~3 texels of 0.66 mm here, |grad T| ~ 1/3 mm) can change
    // it. Unrelated points of this cube differ by years. (Texels are 0.33 mm on the 0.1 m cube.)
    ASSERT_EQ(bake(out_, {"--res", "1024", "--padding", "0"}).exitCode, 0);
    OIIO::ImageBuf growth((out_ / "growth.exr").string());
    OIIO::ImageBuf colour((out_ / "basecolor.exr").string());
    double colourSum = 0, withinSum = 0;
    const double m = 0.02, inset = 1.0 / 1024;
    double worst = 0, sum = 0;
    int n = 0;
    for (int k = 1; k < 40; ++k) {
        double s = k / 40.0;  // along the edge x = 0.1, y = 0.1, z from +0.1 to -0.1
        // +x face: u runs along -z (u from m at z = +0.1), v along +y (v = 0.5 - m at y = +0.1).
        double u0 = m + s * (1.0 / 3 - 2 * m), v0 = 0.5 - m - inset;
        // +y face (chart 2, column 2, row 0): u along +x (u = 1 - m at x = +0.1), v along -z
        // (v = m at z = +0.1).
        double u1 = 1 - m - inset, v1 = m + s * (0.5 - 2 * m);
        float a[2], b[2];
        growth.getpixel(int(u0 * 1024), int((1 - v0) * 1024), a, 2);
        growth.getpixel(int(u1 * 1024), int((1 - v1) * 1024), b, 2);
        float ca[4], cb[4];
        colour.getpixel(int(u0 * 1024), int((1 - v0) * 1024), ca, 4);
        colour.getpixel(int(u1 * 1024), int((1 - v1) * 1024), cb, 4);
        auto colourDistance = [](const float* p, const float* q) {
            return (std::abs(p[0] - q[0]) + std::abs(p[1] - q[1]) + std::abs(p[2] - q[2])) / 3;
        };
        colourSum += colourDistance(ca, cb);
        // The control: two texels of the end-grain chart as far apart as the seam's pair, in
        // the direction that crosses the rings there.
        float cc[4];
        colour.getpixel(int(u1 * 1024) - 2, int((1 - v1) * 1024), cc, 4);
        withinSum += colourDistance(cb, cc);
        double d = std::abs(a[0] - b[0]);
        worst = std::max(worst, d);
        sum += d;
        ++n;
    }
    EXPECT_LT(sum / n, 0.35);  // years
    // The colour changes across the seam no more than across the same distance inside a chart
    // (the late-to-early-wood step is sharp, so neither is small).
    EXPECT_LT(colourSum / n, 1.5 * withinSum / n + 0.01);
    std::printf("seam: mean |dT| %.3f years, max %.3f; mean |d colour| %.4f across, %.4f within\n",
                sum / n, worst, colourSum / n, withinSum / n);
    EXPECT_LT(worst, 1.0);
}

TEST_F(UvBakeCliTest, RenderOfTheBakedCubeMatchesTheDirectRender) {
    fs::path maps = out_ / "maps";
    fs::create_directory(maps);
    ASSERT_EQ(bake(maps, {"--res", "1024"}).exitCode, 0);
    // The same scene, the cube's wood replaced by the baked maps.
    std::string text = readText(kCubeScene);
    auto replace = [&](const std::string& from, const std::string& to) {
        size_t at = text.find(from);
        ASSERT_NE(at, std::string::npos) << from;
        text.replace(at, from.size(), to);
    };
    replace(R"("type": "wood", "skeleton": "../../../scenes/skeletons/conifer.json",
      "grain": "../grain/uv-cube-grain.json", "finish": "matte")",
            fmt::format(R"("type": "textured", "base_colour": "{}", "normal": "{}",
      "fibre": "{}", "finish": "matte")",
                        (maps / "basecolor.exr").string(), (maps / "normal.exr").string(),
                        (maps / "fibre.exr").string()));
    replace(
        R"("file": "../meshes/uv-cube.obj")",
        fmt::format(R"("file": "{}")", (kSourceDir / "tests/data/meshes/uv-cube.obj").string()));
    replace(R"(,
      "log": { "position": [0.01, 0.0, 1.1] })",
            "");
    fs::path textured = in_ / "textured.json";
    std::ofstream(textured) << text;
    ASSERT_EQ(
        run({"render", kCubeScene.string(), "-q", "-o", (out_ / "direct.exr").string()}).exitCode,
        0);
    RunResult r = run({"render", textured.string(), "-q", "-o", (out_ / "baked.exr").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    OIIO::ImageBuf direct((out_ / "direct.exr").string()), baked((out_ / "baked.exr").string());
    auto cmp = OIIO::ImageBufAlgo::compare(direct, baked, 0.05f, 1.0f,
                                           OIIO::ROI(0, 96, 0, 96, 0, 1, 0, 3));
    // Thresholds: texture filtering differs from the direct footprint filter, and the fibre
    // lobe and relief at indirect bounces differ: mean error under 0.01, under 2 % of values
    // off by more than 0.05 (edges of knots and rings).
    EXPECT_LT(cmp.meanerror, 0.01) << "max " << cmp.maxerror;
    EXPECT_LT(cmp.nfail / (96.0 * 96 * 3), 0.02) << "max " << cmp.maxerror;
}

TEST_F(UvBakeCliTest, UnknownObjectIsRejected) {
    RunResult r = run({"bake", "uv", "--scene", kCubeScene.string(), "--object", "chair", "-o",
                       out_.string(), "-q"});
    expectInputError(r, {"no object named \"chair\"", "\"cube\""});
}

TEST_F(UvBakeCliTest, MissingOutputFolderIsRejected) {
    RunResult r = bake(out_ / "nope");
    expectInputError(r, {"-o", "existing folder"});
}

TEST_F(UvBakeCliTest, OverlappingAndOutOfRangeUvsAreReportedNotFatal) {
    // Two triangles on the same uvs, one reaching past u = 1.
    fs::path mesh = in_ / "overlap.obj";
    std::ofstream(mesh) << "v 0 0 0\nv 0.05 0 0\nv 0 0.05 0\nv 0 0 0.05\n"
                           "vt 0.1 0.1\nvt 0.9 0.1\nvt 0.1 0.9\nvt 1.3 0.5\n"
                           "f 1/1 2/2 3/3\nf 1/1 4/4 3/3\n";
    fs::path scene = meshScene(mesh);
    RunResult r = run({"bake", "uv", "--scene", scene.string(), "--object", "tri", "--res", "64",
                       "-o", out_.string(), "-q"});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("overlapping UVs"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("outside [0,1]"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::exists(out_ / "basecolor.exr"));
}

TEST_F(UvBakeCliTest, MeshWithoutUvsIsRejected) {
    fs::path mesh = in_ / "plain.obj";
    std::ofstream(mesh) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    fs::path scene = meshScene(mesh);
    RunResult r = run(
        {"bake", "uv", "--scene", scene.string(), "--object", "tri", "-o", out_.string(), "-q"});
    expectInputError(r, {"texture coordinates"});
}

}  // namespace
