#include "skeleton/sources/kunii/kunii_stand_file.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "tests/scratch_path.h"
#include "util/input_error.h"

namespace nenrin {
namespace {

Stand sampleStand() {
    StandOptions o;
    o.seed = 3;
    o.trees = 20;
    o.plotSize = 20;
    o.years = 25;
    o.schedule = {{0, 1.0}, {20, 0.5}};
    return simulateStand(o);
}

std::string tempPath(const std::string& name) { return scratchPath("kunii-" + name).string(); }

TEST(KuniiStandFile, RoundTripsExactly) {
    Stand stand = sampleStand();
    std::string path = tempPath("stand.json");
    saveStandFile(stand, path);
    Stand back = loadStandFile(path);
    std::remove(path.c_str());
    EXPECT_EQ(standToJson(back).dump(), standToJson(stand).dump());
    ASSERT_EQ(back.trees.size(), stand.trees.size());
    for (size_t i = 0; i < stand.trees.size(); ++i) {
        const StandTree &a = stand.trees[i], &b = back.trees[i];
        EXPECT_EQ(a.species, b.species);
        EXPECT_EQ(a.x, b.x);
        EXPECT_EQ(a.deathYear, b.deathYear);
        ASSERT_EQ(a.history.size(), b.history.size());
        for (size_t k = 0; k < a.history.size(); ++k) {
            EXPECT_EQ(a.history[k].stemRadius, b.history[k].stemRadius);
            EXPECT_EQ(a.history[k].irradiance, b.history[k].irradiance);
        }
    }
    EXPECT_EQ(back.options.schedule.size(), 2u);
    EXPECT_EQ(back.options.law.d, stand.options.law.d);
}

std::string errorOf(const nlohmann::json& j) {
    try {
        standFromJson(j, "stand.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

TEST(KuniiStandFile, BadFilesGiveClearErrors) {
    nlohmann::json good = standToJson(sampleStand());
    auto expectError = [&](nlohmann::json j, const std::string& part) {
        std::string what = errorOf(j);
        EXPECT_NE(what.find("stand.json"), std::string::npos) << what;
        EXPECT_NE(what.find(part), std::string::npos) << what;
    };
    nlohmann::json j = good;
    j["format"] = "nenrin-skeleton";
    expectError(j, "format");
    j = good;
    j.erase("format");
    expectError(j, "nenrin-stand");
    j = good;
    j["trees"][1]["histroy"] = j["trees"][1]["history"];
    expectError(j, "trees[1].histroy");
    j = good;
    j["trees"][2]["history"]["stem_radius"].erase(0);
    expectError(j, "trees[2].history.stem_radius");
    j = good;
    j["irradiance"][3] = -1;
    expectError(j, "irradiance");
    j = good;
    j["options"]["law"]["f"] = 0;
    expectError(j, "options.law.f");
    j = good;
    j["options"]["years"] = -4;
    expectError(j, "options.years");
    j = good;
    j["trees"][0]["id"] = 5;
    expectError(j, "trees[0].id");
    EXPECT_THROW(loadStandFile(tempPath("does-not-exist.json")), InputError);
    std::string path = tempPath("truncated.json");
    {
        std::ofstream f(path);
        f << good.dump().substr(0, 200);
    }
    EXPECT_THROW(loadStandFile(path), InputError);
    std::remove(path.c_str());
}

}  // namespace
}  // namespace nenrin
