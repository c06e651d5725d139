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

TEST(JsonReader, ADuplicateKeyIsRefusedWithItsPath) {
    std::string msg =
        errorOf([] { parseJsonText(R"({"b": [{"gamma": 1, "x": 0, "gamma": 2}]})", "d.json"); });
    EXPECT_NE(msg.find("d.json: b[0].gamma: \"gamma\" a second time"), std::string::npos) << msg;
    // The same key in two objects is fine.
    EXPECT_NO_THROW(parseJsonText(R"([{"a": 1}, {"a": 2}])", "ok.json"));
}

TEST(JsonReader, DeepNestingAndNulBytesAreRefused) {
    std::string deep(65, '[');
    deep += std::string(65, ']');
    std::string msg = errorOf([&] { parseJsonText(deep, "deep.json"); });
    EXPECT_NE(msg.find("nested more than 64 levels"), std::string::npos) << msg;
    EXPECT_NO_THROW(parseJsonText(std::string(64, '[') + std::string(64, ']'), "ok.json"));
    msg = errorOf([] { parseJsonText(std::string("{\"a\": 1}\0{\"b\": 2}", 17), "nul.json"); });
    EXPECT_NE(msg.find("nul.json: line 1, column 9: a NUL byte"), std::string::npos) << msg;
}

TEST(JsonReader, FoldersAndDevicesAreNotJsonFiles) {
    std::string msg = errorOf([] { parseJsonFile("/tmp"); });
    EXPECT_NE(msg.find("this is a folder"), std::string::npos) << msg;
    msg = errorOf([] { parseJsonFile("/dev/zero"); });
    EXPECT_NE(msg.find("not a regular file"), std::string::npos) << msg;
}

TEST(JsonReader, HugeNumbersAreRefused) {
    auto j = parseJsonText(R"({"x": 1e300, "y": -2e9, "z": 1e9})", "h.json");
    JsonReader r(j, "h.json");
    EXPECT_NE(errorOf([&] { r.number("x", 0); }).find("h.json: x: 1e+300 is beyond"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { r.number("y", 0); }).find("beyond"), std::string::npos);
    EXPECT_EQ(r.number("z", 0), 1e9);
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
