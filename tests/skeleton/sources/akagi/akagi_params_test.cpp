// The 13 Akagi parameters: names, ranges, JSON round trip and errors.
#include "skeleton/sources/akagi/akagi_params.h"

#include <gtest/gtest.h>

#include "util/input_error.h"
#include "util/json_reader.h"

namespace nenrin {
namespace {

TEST(AkagiParams, IndexOrderIsThePapers) {
    AkagiParams p;
    p[0] = 11, p[6] = 7, p[12] = 0.9;
    EXPECT_EQ(p.height, 11);
    EXPECT_EQ(p.mainAngle, 7);
    EXPECT_EQ(p.growthGain, 0.9);
    EXPECT_STREQ(akagiParamNames()[4], "BranchNum");
    EXPECT_EQ(akagiParamIndex("SubAngle"), 9);
    EXPECT_EQ(akagiParamIndex("subangle"), -1);
}

TEST(AkagiParams, JsonRoundTripAndStrictReading) {
    AkagiParams p;
    p.subAngle = 62.5, p.leafNum = 12;
    nlohmann::json j = akagiParamsToJson(p);
    JsonReader reader(j, "p.json");
    AkagiParams q = akagiParamsFromJson(reader);
    for (int i = 0; i < kAkagiParamCount; ++i) EXPECT_EQ(p[i], q[i]);

    nlohmann::json bad = nlohmann::json::parse(R"({"Height": 10, "SubGrowht": 0.2})");
    JsonReader badReader(bad, "p.json");
    EXPECT_THROW(akagiParamsFromJson(badReader), InputError);
    nlohmann::json range = nlohmann::json::parse(R"({"MainGrowth": 1.2})");
    JsonReader rangeReader(range, "p.json");
    try {
        akagiParamsFromJson(rangeReader);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.where(), "MainGrowth");
        EXPECT_EQ(e.message(), "expected a number in [0, 1) (share), found 1.2");
    }
}

TEST(AkagiParams, ValidationNamesTheParameter) {
    AkagiParams p;
    p.radius = -0.1;
    try {
        validateAkagiParams(p, "preset keyaki");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "preset keyaki: Radius: expected a number in (0, 5] (m), found -0.1");
    }
}

}  // namespace
}  // namespace nenrin
