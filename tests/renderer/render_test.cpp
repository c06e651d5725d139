// Renderer tests against closed forms and invariants: a Lambert plane under a distant light
// and under a constant sky, wood under two suns as the sum of each alone, white furnaces, bitwise
// determinism across thread counts, and the cut plan's boards (every corner inside the felled log;
// same seed same boards).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <set>
#include <string>

#include "renderer/products/cut_plan.h"
#include "shader/surface_bsdf.h"
#include "tests/renderer/scene_text.h"

namespace nenrin {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = NENRIN_SOURCE_DIR;

std::string woodMaterial(const std::string& name, const std::string& finish = "oiled",
                         const std::string& grain = "scenes/grain/species/norway-spruce.json") {
    return "{\"name\": \"" + name + "\", \"type\": \"wood\", \"skeleton\": \"" +
           (kSource / "scenes/skeletons/conifer.json").string() + "\", \"grain\": \"" +
           (kSource / grain).string() + "\", \"finish\": \"" + finish + "\"}";
}

double meanChannel(const Film& film, int channel) {
    double sum = 0;
    for (size_t i = 0; i < film.alpha.size(); ++i) sum += film.rgb[3 * i + channel];
    return sum / film.alpha.size();
}

/// A camera looking straight down at a large plane (top at y = 0) that fills the view.
std::string planeScene(const std::string& lights, const std::string& material, int spp, int depth) {
    return R"({
      "camera": {"position": [0, 2, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "fov": 30},
      "render": {"resolution": [32, 24], "spp": )" +
           std::to_string(spp) + R"(, "max_depth": )" + std::to_string(depth) + R"(},
      "lights": [)" +
           lights +
           R"(],
      "materials": [)" +
           material +
           R"(],
      "objects": [{"type": "box", "size": [1000, 1, 1000], "position": [0, -0.5, 0],
                   "material": "m"}]
    })";
}

TEST(Render, LambertPlaneUnderDistantLightMatchesClosedForm) {
    // L = albedo E cos(theta) / pi, exactly: next-event estimation of a delta light has no
    // noise, and a lone plane has no interreflection.
    const double albedo = 0.5, E = 2, theta = std::numbers::pi / 6;
    std::string light = R"({"type": "distant", "direction": [)" + std::to_string(std::sin(theta)) +
                        ", " + std::to_string(std::cos(theta)) + R"(, 0], "irradiance": 2})";
    auto scene = sceneFromText(
        "lambert", planeScene(light, R"({"name": "m", "type": "diffuse", "colour": 0.5})", 4, 5));
    Film film = render(*scene);
    double expected = albedo * E * std::cos(theta) / std::numbers::pi;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(meanChannel(film, c), expected, 1e-5 * expected);
    for (float a : film.alpha) EXPECT_EQ(a, 1.f);
}

TEST(Render, WoodUnderTwoSunsIsTheSumOfEachSunAlone) {
    // Camera samples of a pixel share the wood's shading and, towards each sun, its lit value
    // (DirectLight): with two suns every sample must still add each sun's own light. Direct
    // light only, so each pixel is the sum of the two one-sun renders up to rounding.
    const std::string sunA =
        R"({"type": "distant", "direction": [0.3, 0.8, 0.2], "irradiance": 2})";
    const std::string sunB =
        R"({"type": "distant", "direction": [-0.5, 0.6, -0.1], "irradiance": 1.5})";
    auto film = [&](const std::string& lights) {
        return render(*sceneFromText("suns", planeScene(lights, woodMaterial("m"), 8, 1)));
    };
    const Film both = film(sunA + ", " + sunB), a = film(sunA), b = film(sunB);
    double largest = 0;
    for (size_t i = 0; i < both.rgb.size(); ++i) {
        const double sum = double(a.rgb[i]) + double(b.rgb[i]);
        EXPECT_NEAR(both.rgb[i], sum, 1e-5 * sum + 1e-7) << i;
        largest = std::max(largest, sum);
    }
    EXPECT_GT(largest, 0.05);  // the suns do light the wood
    EXPECT_NE(a.rgb, b.rgb);
}

TEST(Render, LambertPlaneUnderConstantSkyMatchesClosedForm) {
    // An infinite plane under a sky of radiance L reflects albedo x L; the ground half of the
    // sky is hidden by the plane. Monte Carlo: within 1 % at 64 spp x 768 pixels.
    // Depth 1 (light sampling alone, no MIS partner) and 2 (MIS with BSDF hits on the sky).
    for (int depth : {1, 2}) {
        auto scene = sceneFromText(
            "sky", planeScene(R"({"type": "environment", "colour": 1.5})",
                              R"({"name": "m", "type": "diffuse", "colour": 0.6})", 64, depth));
        Film film = render(*scene);
        EXPECT_NEAR(meanChannel(film, 1), 0.6 * 1.5, 0.01 * 0.9) << "max_depth " << depth;
    }
}

TEST(Render, WhiteFurnaceDiffuseBoxIsInvisible) {
    // A white Lambert box in a uniform sky of radiance 1 reflects exactly 1 everywhere: the
    // image is 1 whether a pixel sees the box or the sky (RR and MIS must stay unbiased).
    auto scene = sceneFromText("furnace", R"({
      "camera": {"position": [1.5, 1.2, 2.0], "look_at": [0, 0, 0], "fov": 40},
      "render": {"resolution": [32, 24], "spp": 64, "max_depth": 32},
      "lights": [{"type": "environment", "colour": 1}],
      "materials": [{"name": "white", "type": "diffuse", "colour": 1}],
      "objects": [{"type": "box", "size": [1, 1, 1], "material": "white"}]
    })");
    Film film = render(*scene);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(meanChannel(film, c), 1.0, 0.01);
}

TEST(Render, LayeredBsdfsNeverCreateEnergy) {
    // Directional albedo (integral of f cos) <= 1 for the wood, glossy and metal lobes at
    // several view angles, estimated with the BSDF's own sampling.
    SurfaceBsdf wood;
    wood.base = {0.8, 0.8, 0.8};
    wood.coatWeight = 1;
    wood.coatAlpha = 0.05;
    wood.fibre = normalize(Vec3{1, 0, 0.2});
    wood.fibreStrength = 0.35;
    SurfaceBsdf metal;
    metal.metal = true;
    metal.metalF0 = {1, 1, 1};
    metal.metalAlpha = 0.3;
    for (const SurfaceBsdf& b : {wood, metal}) {
        for (double cosTheta : {0.95, 0.6, 0.25}) {
            Vec3 wo{std::sqrt(1 - cosTheta * cosTheta), 0, cosTheta};
            double sum = 0;
            const int n = 200000;
            for (int i = 0; i < n; ++i) {
                SurfaceBsdf::Sample s;
                double u0 = (i + 0.5) / n, u1 = std::fmod(i * 0.7548776662466927, 1.0),
                       u2 = std::fmod(i * 0.5698402909980532, 1.0);
                if (b.sample(wo, u0, u1, u2, s)) sum += s.weight.g;
            }
            EXPECT_LE(sum / n, 1.01) << "cos theta " << cosTheta;
            EXPECT_GT(sum / n, 0.5) << "cos theta " << cosTheta;
        }
    }
}

TEST(Render, BsdfSampleDensityMatchesPdf) {
    // sample() must report the density pdf() gives, or MIS weights are wrong.
    SurfaceBsdf b;
    b.base = {0.5, 0.4, 0.3};
    b.coatWeight = 1;
    b.coatAlpha = 0.1;
    Vec3 wo = normalize(Vec3{0.3, 0.2, 0.9});
    for (int i = 0; i < 1000; ++i) {
        SurfaceBsdf::Sample s;
        if (!b.sample(wo, (i % 10) / 10.0, ((i * 7) % 101) / 101.0, ((i * 13) % 97) / 97.0, s))
            continue;
        EXPECT_NEAR(s.pdf, b.pdf(wo, s.wi), 1e-9 * s.pdf);
    }
}

TEST(Render, PointLightOnLambertPlaneMatchesInverseSquareLaw) {
    // Straight below a point light of intensity I at height h: L = albedo I / (pi h^2); the
    // centre pixel sees nearly that point.
    auto scene = sceneFromText(
        "point", planeScene(R"({"type": "point", "position": [0, 1, 0], "intensity": 5})",
                            R"({"name": "m", "type": "diffuse", "colour": 0.4})", 1, 1));
    Film film = render(*scene);
    size_t centre = size_t(12) * 32 + 16;
    double expected = 0.4 * 5 / std::numbers::pi;
    EXPECT_NEAR(film.rgb[3 * centre], expected, 0.01 * expected);
}

TEST(Render, SmallRectLightActsLikeAPointLight) {
    // Straight below it, a 2 cm square of radiance L facing down is a point light of intensity
    // L x area (its emission falls off as cos, so only the nadir matches): next-event
    // estimation and BSDF hits combined by MIS must give that on a glossy plane. The light
    // hangs off-axis so that its back does not hide the nadir from the camera.
    const double side = 0.02, radiance = 5 / (side * side);
    std::string light = R"({"type": "rect", "corner": [0.29, 1, -0.01], "edge_u": [0.02, 0, 0],
                            "edge_v": [0, 0, 0.02], "radiance": )" +
                        std::to_string(radiance) + "}";
    const std::string glossy =
        R"({"name": "m", "type": "glossy", "colour": 0.4, "roughness": 0.3})";
    auto scene = sceneFromText("rect", planeScene(light, glossy, 256, 2));
    auto reference = sceneFromText(
        "rectref",
        planeScene(R"({"type": "point", "position": [0.3, 1, 0], "intensity": 5})", glossy, 4, 2));
    Film a = render(*scene), b = render(*reference);
    // The nadir (0.3, 0, 0) is seen at pixel x = 22.7, y = 12 (camera at height 2, fov 30).
    double sumA = 0, sumB = 0;
    for (int y = 11; y <= 12; ++y)
        for (int x = 22; x <= 23; ++x) {
            size_t i = 3 * (size_t(y) * 32 + x);
            sumA += a.rgb[i];
            sumB += b.rgb[i];
        }
    EXPECT_NEAR(sumA, sumB, 0.02 * sumB);
}

// A table top seen from 6 m through a 4 degree lens: about four rings per pixel. With the
// ring prefilter and the anatomy faded to its mean under the footprint, one sample per pixel
// is already close to the converged picture (RMSE 0.028 for the two-colour spruce when first
// written); point sampling the rings aliases into moire (RMSE 0.110). Checked for the spruce
// preset (fibres, rays, resin canals) and for oak (large pores and broad rays).
double distantPlankRmse(const std::string& grain) {
    auto make = [&](int spp) {
        return sceneFromText("plank" + std::to_string(spp) + fs::path(grain).stem().string(),
                             R"({
          "camera": {"position": [0, 6, 0], "look_at": [0, 0, 0], "up": [0, 0, -1],
                     "fov": 4},
          "render": {"resolution": [64, 32], "spp": )" +
                                 std::to_string(spp) +
                                 R"(, "max_depth": 1},
          "lights": [{"type": "sun", "direction": [0.2, 1, 0.3], "irradiance": 3}],
          "materials": [)" + woodMaterial("w", "matte", grain) +
                                 R"(],
          "objects": [{"type": "table_top", "boards": 6, "length": 4.5, "width": 0.6,
                       "thickness": 0.03, "position": [0, -0.015, 0], "material": "w",
                       "cut": {"seed": 2, "sawing": "flat", "top": 6}}]
        })");
    };
    Film one = render(*make(1)), many = render(*make(64));
    double sum = 0, n = 0;
    for (size_t i = 0; i < one.rgb.size(); ++i) {
        double d = one.rgb[i] - many.rgb[i];
        sum += d * d;
        n += 1;
    }
    return std::sqrt(sum / n);
}

TEST(Render, DistantPlankAtOneSampleShowsNoMoire) {
    double spruce = distantPlankRmse("scenes/grain/species/norway-spruce.json");
    double oak = distantPlankRmse("scenes/grain/species/european-oak.json");
    RecordProperty("rmse_1spp_vs_64spp_spruce", std::to_string(spruce));
    RecordProperty("rmse_1spp_vs_64spp_oak", std::to_string(oak));
    std::printf("distant plank: RMSE of 1 spp against 64 spp %.4f (spruce), %.4f (oak)\n", spruce,
                oak);
    EXPECT_LT(spruce, 0.05);
    EXPECT_LT(oak, 0.05);
}

std::unique_ptr<Scene> smallGlulam(uint64_t cutSeed, int spp = 2) {
    return sceneFromText("glulam" + std::to_string(cutSeed), R"({
      "camera": {"position": [0.9, 0.35, 0.5], "look_at": [0.4, 0, 0], "fov": 40},
      "render": {"resolution": [48, 32], "spp": )" + std::to_string(spp) +
                                                                 R"(, "max_depth": 3},
      "lights": [{"type": "sun", "direction": [0.4, 0.8, 0.45], "irradiance": 3},
                 {"type": "environment", "colour": [0.3, 0.35, 0.45]}],
      "materials": [)" + woodMaterial("spruce") +
                                                                 R"(],
      "objects": [{"type": "glulam", "lamellae": 6, "lamella_thickness": 0.04,
                   "width": 0.14, "length": 1.2, "finger_joints": {"min_length": 0.5,
                   "max_length": 0.9}, "cut": {"seed": )" + std::to_string(cutSeed) +
                                                                 R"(},
                   "material": "spruce"}]
    })");
}

TEST(Render, SameBytesForOneAndTwoThreads) {
    auto scene = smallGlulam(3);
    Film a = render(*scene, 1), b = render(*scene, 2);
    EXPECT_EQ(a.rgb, b.rgb);
    EXPECT_EQ(a.albedo, b.albedo);
    EXPECT_EQ(a.growthTime, b.growthTime);
    EXPECT_EQ(a.lamella, b.lamella);
    EXPECT_EQ(a.normal, b.normal);
}

TEST(Render, AovsNameTheBoardsAndTheirGrowthTime) {
    auto scene = smallGlulam(3);
    Film film = render(*scene);
    std::set<int> ids;
    for (size_t i = 0; i < film.lamella.size(); ++i) {
        if (film.lamella[i] < 0) continue;
        ids.insert(static_cast<int>(film.lamella[i]));
        EXPECT_GT(film.growthTime[i], 0.f);
        EXPECT_LE(film.growthTime[i], 40.5f);  // norway-spruce.json: felled at 40 years
    }
    EXPECT_GE(ids.size(), 4u);  // the end and the side show several lamellae
}

TEST(CutPlan, BoardsDifferAndTheSameSeedGivesTheSameBoards) {
    auto a = smallGlulam(3), b = smallGlulam(3), c = smallGlulam(4);
    const auto& la = a->objects[0].layout->lamellae;
    const auto& lb = b->objects[0].layout->lamellae;
    const auto& lc = c->objects[0].layout->lamellae;
    ASSERT_EQ(la.size(), lb.size());
    ASSERT_GE(la.size(), 6u);
    for (size_t i = 0; i < la.size(); ++i) {
        EXPECT_EQ(la[i].treeFromLamella.origin, lb[i].treeFromLamella.origin);
        EXPECT_EQ(la[i].treeFromLamella.y, lb[i].treeFromLamella.y);
        if (i > 0) {
            EXPECT_NE(la[i].treeFromLamella.origin, la[i - 1].treeFromLamella.origin);
        }
    }
    EXPECT_NE(la[0].treeFromLamella.origin, lc[0].treeFromLamella.origin);
}

TEST(CutPlan, EveryBoardCornerLiesInsideTheFelledLog) {
    auto scene = smallGlulam(11);
    const SceneObject& beam = scene->objects[0];
    const GrowthField& field = scene->materials[0].wood->field();
    for (const Lamella& l : beam.layout->lamellae) {
        for (int corner = 0; corner < 8; ++corner) {
            Vec3 p{corner & 1 ? l.upper.x : l.lower.x, corner & 2 ? l.upper.y : l.lower.y,
                   corner & 4 ? l.upper.z : l.lower.z};
            double T = field.evaluate(l.treeFromProduct.point(p)).T;
            EXPECT_LE(T, field.params().fellingTime) << "lamella " << l.id << " corner " << corner;
        }
    }
}

TEST(CutPlan, FlatAndQuarterSawnBoardsFaceTheRingsAsNamed) {
    // Flat-sawn: the wide face (lamella z = thickness axis) points along the radius;
    // quarter-sawn: the width axis does.
    auto scene = smallGlulam(5);
    const GrowthField& field = scene->materials[0].wood->field();
    CutPlanParams plan;
    for (Sawing sawing : {Sawing::Flat, Sawing::Quarter}) {
        plan.sawing = sawing;
        for (uint64_t i = 0; i < 8; ++i) {
            auto cut = cutBoard(field, plan, 1.0, 0.08, 0.03, i);
            ASSERT_TRUE(cut);
            Vec3 radial{std::cos(cut->azimuth), std::sin(cut->azimuth), 0};
            const Vec3& axis =
                sawing == Sawing::Flat ? cut->treeFromLamella.z : cut->treeFromLamella.y;
            EXPECT_NEAR(std::abs(dot(axis, radial)), 1.0, 1e-12);
            EXPECT_EQ(cut->quarterSawn, sawing == Sawing::Quarter);
        }
    }
}

}  // namespace
}  // namespace nenrin
