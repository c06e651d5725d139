#include "util/json_reader.h"

#include <gtest/gtest.h>

namespace nenrin {
namespace {

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(JsonReader, SyntaxErrorNamesLineAndColumn) {
    std::string msg = errorOf([] { parseJsonText("{\n  \"a\": 1,\n  \"b\": ]\n}", "f.json"); });
    EXPECT_NE(msg.find("f.json: line 3, column 8: invalid JSON"), std::string::npos) << msg;
}

TEST(JsonReader, TruncatedFileIsCalledTruncated) {
    std::string msg = errorOf([] { parseJsonText("{\"a\": [1, 2", "t.json"); });
    EXPECT_NE(msg.find("t.json: line 1"), std::string::npos) << msg;
    EXPECT_NE(msg.find("truncated"), std::string::npos) << msg;
}

TEST(JsonReader, UnknownKeyIsRejectedWithItsPath) {
    auto j = parseJsonText(R"({"outer": {"good": 1, "bda": 2}})", "k.json");
    std::string msg = errorOf([&] {
        JsonReader r(j, "k.json");
        auto o = r.object("outer");
        o->number("good", 0);
        o->finish();
    });
    EXPECT_EQ(msg, "k.json: outer.bda: unknown key (misspelled? see the format documentation)");
}

TEST(JsonReader, TypedReadsCheckTypeRangeAndFiniteness) {
    EXPECT_EQ(errorOf([] { parseJsonText("{\n \"big\": 1e999}", "o.json"); }),
              "o.json: line 2, column 9: number out of range (1e999): expected a finite number");
    auto j = parseJsonText(R"({"s": "x", "n": -1, "v": [1, 2]})", "t.json");
    JsonReader r(j, "t.json");
    EXPECT_EQ(errorOf([&] { r.number("s", 0); }), "t.json: s: expected a number, found a string");
    EXPECT_EQ(errorOf([&] { r.positive("n", 1); }), "t.json: n: expected a number > 0, found -1");
    EXPECT_EQ(errorOf([&] { r.requireVec3("v"); }),
              "t.json: v: expected an array of 3 numbers [x, y, z], found 2 elements");
    EXPECT_EQ(errorOf([&] { r.requireNumber("missing"); }),
              "t.json: missing: missing required number");
    EXPECT_DOUBLE_EQ(r.number("absent", 4.5), 4.5);
}

TEST(JsonReader, ListElementsAreNamedByIndex) {
    auto j = parseJsonText(R"({"pts": [[0, 0, 0], [0, "a", 1]]})", "p.json");
    JsonReader r(j, "p.json");
    EXPECT_EQ(errorOf([&] { r.requireVec3List("pts"); }),
              "p.json: pts[1][1]: expected a number, found a string");
}

}  // namespace
}  // namespace nenrin
