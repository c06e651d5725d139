// Light selection (many lights): the sun and the sky are sampled at every vertex and one point
// or rectangle light is picked, as often as probability() says; a light gets importance 0 only
// where it cannot light the point; images with one light picked per vertex converge to the
// every-light images (coloured point lights, whose every-light image has no noise; rectangles
// and a sky through multiple importance sampling), the same bytes for any thread count.

#include "renderer/light_selection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <string>

#include "renderer/lights.h"
#include "tests/renderer/scene_text.h"

namespace nenrin {
namespace {

namespace fs = std::filesystem;

/// Twelve point lights of different intensities and colours over the origin, a sun, a
/// one-sided rectangle facing down, one facing up (dark from above) and a constant sky.
std::vector<Light> manyLights() {
    std::vector<Light> lights;
    for (int i = 0; i < 12; ++i) {
        Light l;
        l.type = LightType::Point;
        l.position = {std::cos(i * 0.52) * (0.5 + 0.2 * i), 0.8 + 0.1 * (i % 4),
                      std::sin(i * 0.52) * (0.5 + 0.2 * i)};
        l.power = Rgb{0.5 + 0.3 * (i % 3), 0.6, 0.2 + 0.1 * i};
        lights.push_back(l);
    }
    Light sun;
    sun.direction = normalize(Vec3{0.3, 1, 0.2});
    sun.power = {2, 2, 1.8};
    lights.push_back(sun);
    for (double facing : {-1.0, 1.0}) {
        Light r;
        r.type = LightType::Rect;
        r.corner = {-0.3, 1.5, -0.2};
        r.edgeU = {0.6, 0, 0};
        r.edgeV = {0, 0, 0.4 * facing};
        Vec3 n = cross(r.edgeU, r.edgeV);
        r.area = length(n);
        r.normal = n / r.area;
        r.power = {3, 3, 3};
        lights.push_back(r);
    }
    Light sky;
    sky.type = LightType::Environment;
    sky.environment = std::make_shared<EnvironmentMap>(EnvironmentMap::constant({0.3, 0.4, 0.6}));
    lights.push_back(sky);
    return lights;
}

TEST(LightSelection, PicksEachLightAsOftenAsItsProbabilitySays) {
    const std::vector<Light> lights = manyLights();
    LightSelection selection(lights, LightSelectionMode::Auto);
    ASSERT_TRUE(selection.picksOne());
    // The sun and the sky at every vertex; one of the points and rectangles picked.
    ASSERT_EQ(selection.everyVertex(), (std::vector<uint32_t>{12, 15}));
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> coordinate(-2, 2);
    std::vector<double> cdf;
    const int n = 200000;
    for (int trial = 0; trial < 20; ++trial) {
        Vec3 p{coordinate(random), coordinate(random) * 0.5, coordinate(random)};
        Vec3 normal =
            normalize(Vec3{coordinate(random), 2 + coordinate(random), coordinate(random)});
        std::vector<int> count(lights.size() + 1, 0);
        for (int k = 0; k < n; ++k) {
            double probability = -1;
            size_t i = selection.select(p, normal, (k + 0.5) / n, probability, cdf);
            ASSERT_LE(i, lights.size());
            if (i < lights.size()) {
                EXPECT_EQ(probability, selection.probability(i, p, normal)) << "light " << i;
            }
            ++count[i];
        }
        double sum = 0;
        for (size_t i = 0; i < lights.size(); ++i) {
            const double expected = selection.probability(i, p, normal);
            if (i == 12 || i == 15) {
                EXPECT_EQ(expected, 1);
                EXPECT_EQ(count[i], 0);
                continue;
            }
            sum += expected;
            // Stratified u: each light's share is its probability to within 1/n.
            EXPECT_NEAR(count[i] / double(n), expected, 2.0 / n)
                << "trial " << trial << " light " << i;
        }
        if (count[lights.size()] == n) {
            EXPECT_EQ(sum, 0);  // no local light reaches p
        } else {
            EXPECT_EQ(count[lights.size()], 0);
            EXPECT_NEAR(sum, 1, 1e-12);
        }
    }
}

TEST(LightSelection, ImportanceIsZeroOnlyWhereALightCannotReach) {
    // Where a light has importance 0, none of its samples may light the point (a sample below
    // the horizon of n lights nothing): selection would otherwise lose its light.
    const std::vector<Light> lights = manyLights();
    std::mt19937_64 random(11);
    std::uniform_real_distribution<double> coordinate(-2.5, 2.5);
    int zeros = 0, positives = 0;
    for (int trial = 0; trial < 400; ++trial) {
        Vec3 p{coordinate(random), coordinate(random), coordinate(random)};
        Vec3 normal = normalize(Vec3{coordinate(random), coordinate(random), coordinate(random)});
        for (const Light& light : lights) {
            const double importance = LightSelection::importance(light, p, normal);
            ASSERT_GE(importance, 0);
            ASSERT_TRUE(std::isfinite(importance));
            if (importance > 0) {
                ++positives;
                continue;
            }
            ++zeros;
            for (int k = 0; k < 256; ++k) {
                LightSample s;
                if (!sampleLight(light, p, (k % 16 + 0.5) / 16, (k / 16 + 0.5) / 16, s)) continue;
                const bool lights = dot(s.direction, normal) > 0 &&
                                    (s.radiance.r > 0 || s.radiance.g > 0 || s.radiance.b > 0);
                EXPECT_FALSE(lights) << "trial " << trial << ": a light of importance 0 lights p";
            }
        }
    }
    EXPECT_GT(zeros, 400);  // the test saw lights below horizons and behind rectangles
    EXPECT_GT(positives, 400);
}

TEST(LightSelection, OddsStayFiniteRightNextToALight) {
    // A point 1e-120 m under a point light: intensity x cos / d^2 overflows, d^3 underflows.
    std::vector<Light> lights = manyLights();
    lights[3].position = {0, 0, 0};
    LightSelection selection(lights, LightSelectionMode::Importance);
    const Vec3 p{0, -1e-120, 0}, up{0, 1, 0};
    std::vector<double> cdf;
    double probability = 0;
    EXPECT_EQ(selection.select(p, up, 0.5, probability, cdf), 3u);
    EXPECT_GT(probability, 0.99);
    EXPECT_LE(probability, 1);
    for (size_t i = 0; i < lights.size(); ++i)
        EXPECT_TRUE(std::isfinite(selection.probability(i, p, up))) << "light " << i;
}

TEST(LightSelection, AutoPicksOneLocalLightPastTwo) {
    std::vector<Light> lights = manyLights();  // points 0-11, sun 12, rectangles 13-14, sky 15
    auto everyLight = [](const LightSelection& s, size_t count) {
        return !s.picksOne() && s.everyVertex().size() == count;
    };
    std::vector<Light> few{lights[0], lights[12], lights[13], lights[15]};
    EXPECT_TRUE(everyLight(LightSelection(few, LightSelectionMode::Auto), 4));
    EXPECT_TRUE(LightSelection(few, LightSelectionMode::Importance).picksOne());
    few.push_back(lights[1]);
    const LightSelection three(few, LightSelectionMode::Auto);
    EXPECT_TRUE(three.picksOne());
    EXPECT_EQ(three.everyVertex(), (std::vector<uint32_t>{1, 3}));
    EXPECT_TRUE(everyLight(LightSelection(few, LightSelectionMode::All), 5));
    // A sun and a sky alone: nothing to pick, whatever the mode.
    std::vector<Light> sky{lights[12], lights[15]};
    EXPECT_TRUE(everyLight(LightSelection(sky, LightSelectionMode::Importance), 2));
}

/// A camera looking down at a large plane (top at y = 0) under `lights`.
std::string planeScene(const std::string& lights, const std::string& material, int spp, int depth,
                       const std::string& selection) {
    return R"({
      "camera": {"position": [0, 2, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "fov": 50},
      "render": {"resolution": [32, 24], "spp": )" +
           std::to_string(spp) + R"(, "max_depth": )" + std::to_string(depth) +
           R"(, "light_selection": ")" + selection + R"("},
      "lights": [)" +
           lights + R"(],
      "materials": [)" +
           material + R"(],
      "objects": [{"type": "box", "size": [1000, 1, 1000], "position": [0, -0.5, 0],
                   "material": "m"}]
    })";
}

/// Ten point lights of different intensities and colours, some low over the plane (sharp pools
/// of light). The colours matter: on a Lambert plane, picking by luminance would otherwise be
/// perfect importance sampling, with no noise to test.
std::string pointLights() {
    std::string text;
    for (int i = 0; i < 10; ++i) {
        if (i) text += ", ";
        text +=
            R"({"type": "point", "position": [)" + std::to_string(std::cos(i * 0.7) * 0.8) + ", " +
            std::to_string(0.25 + 0.15 * (i % 5)) + ", " + std::to_string(std::sin(i * 0.7) * 0.6) +
            R"(], "intensity": )" + std::to_string(0.1 + 0.05 * i) + R"(, "colour": [)" +
            std::to_string(0.3 + 0.7 * (i % 2)) + ", " + std::to_string(0.2 + 0.08 * i) + ", 0.5]}";
    }
    return text;
}

struct Difference {
    double meanRatio;     ///< image mean / reference image mean (green)
    double relativeRmse;  ///< per-pixel RMSE over the reference mean
};

Difference compare(const Film& image, const Film& reference) {
    double sum = 0, sumReference = 0, squares = 0;
    const size_t n = image.alpha.size();
    for (size_t i = 0; i < n; ++i) {
        const double a = image.rgb[3 * i + 1], b = reference.rgb[3 * i + 1];
        sum += a;
        sumReference += b;
        squares += (a - b) * (a - b);
    }
    return {sum / sumReference, std::sqrt(squares / n) / (sumReference / n)};
}

TEST(LightSelection, PointLightsOnALambertPlaneConvergeToTheEveryLightImage) {
    // Direct light only: sampling every point light has no noise, so that image is the closed
    // form (at the same 256 camera samples a pixel, the same points on the plane). One light
    // picked per vertex is unbiased: its mean over 256 samples a pixel is within 0.5 % over
    // the image (0.05 % when written), and each pixel within 3 % (RMSE 0.9 % when written).
    const std::string material = R"({"name": "m", "type": "diffuse", "colour": 0.5})";
    auto every = sceneFromText("points-all", planeScene(pointLights(), material, 256, 1, "all"));
    auto picked = sceneFromText("points-one", planeScene(pointLights(), material, 256, 1, "auto"));
    Difference d = compare(render(*picked), render(*every));
    EXPECT_NEAR(d.meanRatio, 1, 0.005);
    EXPECT_LT(d.relativeRmse, 0.03);
}

TEST(LightSelection, RectanglesAndSkyUnderMisConvergeToTheEveryLightImage) {
    // Glossy plane, direct light and one bounce: rectangles and the sky are found both by
    // light samples and by BSDF samples, weighted by MIS, whose light density must include the
    // probability of picking the light. Both images at 1024 samples a pixel: the means agreed
    // to 0.06 % when written; leaving that probability out of the BSDF hits' weights made
    // them 0.9 % apart.
    std::string lights;
    for (int i = 0; i < 6; ++i) {
        const double x = -0.9 + 0.3 * i, y = 0.3 + 0.12 * i;
        lights += R"({"type": "rect", "corner": [)" + std::to_string(x) + ", " + std::to_string(y) +
                  R"(, -0.2], "edge_u": [0.15, 0, 0], "edge_v": [0, 0, 0.4],
                      "radiance": )" +
                  std::to_string(2 + i) + "}, ";
    }
    lights += R"({"type": "environment", "colour": 0.2})";
    const std::string glossy =
        R"({"name": "m", "type": "glossy", "colour": 0.4, "roughness": 0.1})";
    auto every = sceneFromText("rects-all", planeScene(lights, glossy, 1024, 2, "all"));
    auto picked = sceneFromText("rects-one", planeScene(lights, glossy, 1024, 2, "importance"));
    Difference d = compare(render(*picked), render(*every));
    EXPECT_NEAR(d.meanRatio, 1, 0.005);
}

TEST(LightSelection, TheBundledShowroomPicksOneLightPerVertex) {
    auto scene =
        loadScene((fs::path(NENRIN_SOURCE_DIR) / "scenes/showroom-downlights.json").string());
    EXPECT_EQ(scene->lights.size(), 15u);
    EXPECT_EQ(scene->settings.lightSelection, LightSelectionMode::Auto);
    EXPECT_TRUE(LightSelection(scene->lights, scene->settings.lightSelection).picksOne());
}

TEST(LightSelection, SameBytesForOneAndTwoThreads) {
    const std::string material = R"({"name": "m", "type": "diffuse", "colour": 0.5})";
    auto scene =
        sceneFromText("points-threads", planeScene(pointLights(), material, 16, 3, "auto"));
    Film a = render(*scene, 1), b = render(*scene, 2);
    EXPECT_EQ(a.rgb, b.rgb);
}

}  // namespace
}  // namespace nenrin
