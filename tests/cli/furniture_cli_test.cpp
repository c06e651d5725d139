// nenrin furniture (issue 33) on a real model, the oak chair of Debian's sweethome3d-furniture
// (tests/data/furniture/oak-chair, CC0): its seventeen pieces each become a board, legs with
// their fibre along the leg, no two boards from one place; the scene it writes puts every part
// where the plan says; a plan edited and passed back is followed; bad models are refused.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/cli/cli_fixture.h"

namespace nenrin {
namespace {

const fs::path kChair = kSourceDir / "tests/data/furniture/oak-chair/oakChair.obj";

class FurnitureCliTest : public CliTest {
protected:
    RunResult furniture(const std::vector<std::string>& extra) {
        std::vector<std::string> args = {
            "furniture", kChair.string(),
            "--grain",   grainScene("species/european-oak.json").string(),
            "--unit",    "cm",
            "--res",     "32",
            "--preview", "64",
            "-q",        "--threads",
            "2"};
        args.insert(args.end(), extra.begin(), extra.end());
        return run(args);
    }
    nlohmann::json json(const fs::path& p) { return nlohmann::json::parse(readText(p)); }
};

/// The longest principal axis of a part's vertices (unweighted, by power iteration): an
/// estimate independent of nenrin's area-weighted one.
std::array<double, 3> vertexAxis(const fs::path& obj) {
    std::vector<std::array<double, 3>> v;
    std::istringstream in(readText(obj));
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("v ", 0) == 0) {
            std::array<double, 3> p;
            std::sscanf(line.c_str(), "v %lf %lf %lf", &p[0], &p[1], &p[2]);
            v.push_back(p);
        }
    double mean[3] = {0, 0, 0}, c[3][3] = {};
    for (auto& p : v)
        for (int i = 0; i < 3; ++i) mean[i] += p[i] / double(v.size());
    for (auto& p : v)
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) c[i][j] += (p[i] - mean[i]) * (p[j] - mean[j]);
    std::array<double, 3> a = {1, 1, 1};
    for (int it = 0; it < 200; ++it) {
        std::array<double, 3> b = {0, 0, 0};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) b[i] += c[i][j] * a[j];
        const double n = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
        for (int i = 0; i < 3; ++i) a[i] = b[i] / n;
    }
    return a;
}

TEST_F(FurnitureCliTest, EveryPieceOfTheChairIsItsOwnBoard) {
    auto r = furniture({"-o", (out_ / "chair").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json plan = json(out_ / "chair/parts.json");
    const auto& parts = plan["parts"];
    // Seven objects holding seventeen separate pieces (tests/data/furniture/oak-chair).
    ASSERT_EQ(parts.size(), 17u);
    std::set<std::string> names, places;
    int legs = 0;
    for (const auto& p : parts) {
        names.insert(p["name"]);
        ASSERT_TRUE(p["wood"].get<bool>()) << p.dump();
        places.insert(p["tree_from_model"]["origin"].dump());
        const auto size = p["size"];
        const std::string name = p["name"];
        // Elongated parts: the fibre within 5 degrees of the vertices' principal axis.
        if (size[0].get<double>() > 2 * size[1].get<double>()) {
            size_t index = &p - &parts[0];
            fs::path obj;
            for (const auto& e : fs::directory_iterator(out_ / "chair/parts"))
                if (e.path().filename().string().rfind(fmt::format("{:03d}-", index), 0) == 0)
                    obj = e.path();
            ASSERT_FALSE(obj.empty()) << name;
            const auto axis = vertexAxis(obj);
            const double cosine = std::abs(axis[0] * p["fibre"][0].get<double>() +
                                           axis[1] * p["fibre"][1].get<double>() +
                                           axis[2] * p["fibre"][2].get<double>());
            EXPECT_GT(cosine, std::cos(5 * M_PI / 180)) << name;
        }
        // The legs (one object, four pieces) stand: their fibre within 20 degrees of +y.
        if (name.rfind("Circle.011_Circle.016.", 0) == 0) {
            ++legs;
            EXPECT_GT(std::abs(p["fibre"][1].get<double>()), std::cos(20 * M_PI / 180)) << name;
        }
    }
    EXPECT_EQ(legs, 4);
    EXPECT_EQ(names.size(), 17u);   // one name each
    EXPECT_EQ(places.size(), 17u);  // no two boards from one place in the log
    for (const char* f : {"scene.json", "preview.png", "skeleton.json"})
        EXPECT_TRUE(fs::exists(out_ / "chair" / f)) << f;
    // Every wood part its texture set (the glTF validator checks them: ctest gltf_validator).
    for (const auto& p : parts) {
        const fs::path set = out_ / "chair" / p["textures"].get<std::string>();
        EXPECT_TRUE(fs::exists(set / "basecolor.png")) << set;
        auto base = readImage(set / "basecolor.png");
        ASSERT_TRUE(base);
        EXPECT_EQ(base->spec.width, 32);
    }
    auto preview = readImage(out_ / "chair/preview.png");
    ASSERT_TRUE(preview);
    EXPECT_EQ(preview->spec.width, 64);
}

TEST_F(FurnitureCliTest, ThePlanEditedIsFollowed) {
    ASSERT_EQ(furniture({"-o", (out_ / "a").string()}).exitCode, 0);
    nlohmann::json plan = json(out_ / "a/parts.json");
    // The seat is not wood (upholstered); a leg's fibre turned across it; another seed.
    plan["parts"][9]["wood"] = false;
    plan["parts"][5]["fibre"] = {1, 0, 0};
    plan["parts"][6]["seed"] = 1234;
    plan["parts"].push_back({{"name", "cushion"}, {"wood", false}});  // not in the model
    std::ofstream(out_ / "plan.json") << plan.dump(1);
    auto r = furniture({"-o", (out_ / "b").string(), "--plan", (out_ / "plan.json").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("part \"cushion\" is not in the model"), std::string::npos) << r.err;
    const nlohmann::json again = json(out_ / "b/parts.json");
    EXPECT_FALSE(again["parts"][9]["wood"].get<bool>());
    EXPECT_NEAR(std::abs(again["parts"][5]["fibre"][0].get<double>()), 1, 1e-12);
    EXPECT_EQ(again["parts"][6]["seed"], 1234);
    EXPECT_NE(again["parts"][6]["board"].dump(), plan["parts"][6]["board"].dump());
    EXPECT_EQ(again["parts"][7]["board"].dump(), plan["parts"][7]["board"].dump());
    const nlohmann::json scene = json(out_ / "b/scene.json");
    EXPECT_EQ(scene["objects"][9]["material"], "not-wood");
    EXPECT_NE(scene["objects"][8]["material"], "not-wood");
}

TEST_F(FurnitureCliTest, BadModelsAreRefusedAndLeaveNothing) {
    std::ofstream(in_ / "empty.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    std::ofstream(in_ / "nan.obj") << "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n";
    auto with = [&](const fs::path& model, std::vector<std::string> extra) {
        std::vector<std::string> args = {
            "furniture", model.string(),
            "--grain",   grainScene("species/european-oak.json").string(),
            "-o",        (out_ / "x").string()};
        args.insert(args.end(), extra.begin(), extra.end());
        return run(args);
    };
    expectInputError(with(in_ / "empty.obj", {}), {"empty.obj", "no faces"});
    expectInputError(with(in_ / "nan.obj", {}), {"nan.obj", "line 2"});
    expectInputError(with(in_ / "missing.obj", {}), {"missing.obj"});
    std::ofstream(in_ / "plan.json")
        << R"({"parts": [{"name": "x", "requested_sawing": "diagonal"}]})";
    expectInputError(with(kChair, {"--unit", "cm", "--plan", (in_ / "plan.json").string()}),
                     {"plan.json", "requested_sawing", "diagonal"});
}

TEST_F(FurnitureCliTest, AModelOfImplausibleSizeIsWarnedAbout) {
    auto with = [&](const std::string& unit, const std::string& folder) {
        return run({"furniture", kChair.string(), "--grain",
                    grainScene("species/european-oak.json").string(), "--unit", unit, "--res", "0",
                    "--preview", "32", "-q", "-o", (out_ / folder).string()});
    };
    // The chair is in centimetres. Read as millimetres it is 15 cm across: said, and done.
    auto small = with("mm", "small");
    EXPECT_EQ(small.exitCode, 0) << small.err;
    EXPECT_NE(small.err.find("implausible for furniture"), std::string::npos) << small.err;
    // Read as metres (150 m), its boards fit no log: the error says why it is likely.
    fs::remove_all(out_ / "small");
    expectInputError(with("m", "huge"), {"fits in the log", "--unit m", "implausible"});
}

}  // namespace
}  // namespace nenrin
