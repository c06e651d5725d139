#include "util/json_parse.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "util/input_error.h"

namespace nenrin {
namespace {

::testing::AssertionResult sameDocument(const nlohmann::json& a, const nlohmann::json& b) {
    const std::string difference = jsonDifference(a, b);
    if (difference.empty()) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << difference;
}

/// The property parseJsonText rests on: where the fast parser answers, the careful one gives
/// the same document (and does not refuse it).
::testing::AssertionResult fastAgrees(const std::string& text) {
    std::optional<nlohmann::json> fast = parseJsonFast(text);
    if (!fast) return ::testing::AssertionSuccess();
    try {
        return sameDocument(*fast, parseJsonReportingErrors(text, "t.json"));
    } catch (const InputError& e) {
        return ::testing::AssertionFailure() << "fast parser took what is refused: " << e.what();
    }
}

std::string readFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

TEST(JsonParse, JsonDifferenceSeesTypesBitsAndPaths) {
    using nlohmann::json;
    EXPECT_EQ(jsonDifference(json::parse(R"({"a": [1, 2.5]})"), json::parse(R"({"a": [1, 2.5]})")),
              "");
    // 1 and 1.0 compare equal in nlohmann; not here.
    EXPECT_NE(jsonDifference(json::parse("[1]"), json::parse("[1.0]")).find("[0]: types differ"),
              std::string::npos);
    EXPECT_NE(jsonDifference(json::parse("-0.0"), json::parse("0.0")).find("float bits differ"),
              std::string::npos);
    EXPECT_NE(jsonDifference(json::parse(R"({"a": {"b": 1}})"), json::parse(R"({"a": {"c": 1}})"))
                  .find("a: keys differ"),
              std::string::npos);
    EXPECT_NE(
        jsonDifference(json::parse(R"({"a": {"b": "x"}})"), json::parse(R"({"a": {"b": "y"}})"))
            .find("a.b: values differ"),
        std::string::npos);
    EXPECT_NE(jsonDifference(json::parse("7"), json::parse("-7")).find("types differ"),
              std::string::npos);
    // The one allowed difference: a signed and an unsigned 0.
    EXPECT_EQ(jsonDifference(json::parse("-0"), json::parse("0")), "");
}

TEST(JsonParse, TakesOrdinaryDocumentsAsNlohmannDoes) {
    for (const char* text : {"0",
                             "-0",
                             "-0.0",
                             "0.0",
                             "1e-400",
                             "-1e-400",
                             "4.9e-324",
                             "2.2250738585072011e-308",
                             "1.7976931348623157e308",
                             "18446744073709551615",
                             "-9223372036854775808",
                             "9223372036854775807",
                             "9223372036854775808",
                             "1.0",
                             "1e2",
                             "1E+2",
                             "0.1e-1",
                             R"("a\u0000b")",
                             R"("\ud83d\ude00")",
                             "\"\xc3\xa9\"",
                             R"("\/\"\\\b\f\n\r\t")",
                             R"({"": 0, "a": [true, false, null], "b": {"c": [[], {}]}})",
                             " [1, 2.5, -3] \n",
                             R"({"z": 1, "a": 2})"}) {
        SCOPED_TRACE(text);
        ASSERT_TRUE(parseJsonFast(text).has_value());
        EXPECT_TRUE(fastAgrees(text));
        EXPECT_TRUE(sameDocument(parseJsonText(text, "t.json"), nlohmann::json::parse(text)));
    }
    // Number types as nlohmann keeps them: unsigned without a sign, signed with one.
    EXPECT_TRUE(parseJsonFast("7")->is_number_unsigned());
    EXPECT_TRUE(parseJsonFast("-7")->is_number_integer());
    EXPECT_FALSE(parseJsonFast("-7")->is_number_unsigned());
    EXPECT_TRUE(parseJsonFast("7.0")->is_number_float());
}

TEST(JsonParse, LeavesToNlohmannWhatOnlyItTakes) {
    // Integers past 64 bits (nlohmann: the nearest double) and a byte-order mark.
    for (const char* text : {"18446744073709551616", "-9223372036854775809",
                             "123456789012345678901234567890", "\xef\xbb\xbf{\"a\": 1}"}) {
        SCOPED_TRACE(text);
        EXPECT_FALSE(parseJsonFast(text).has_value());
        EXPECT_TRUE(sameDocument(parseJsonText(text, "t.json"), nlohmann::json::parse(text)));
    }
}

TEST(JsonParse, RefusesWhatTheStrictReaderRefusesWithTheSameMessages) {
    auto message = [](const std::string& text) {
        try {
            parseJsonText(text, "f.json");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    const std::string duplicate = R"({"b": [{"gamma": 1, "gamma": 2}]})";
    EXPECT_FALSE(parseJsonFast(duplicate).has_value());
    EXPECT_NE(message(duplicate).find("f.json: b[0].gamma: \"gamma\" a second time"),
              std::string::npos);
    // 64 levels are read; the 65th is refused.
    const std::string deepest = std::string(kMaxJsonDepth, '[') + std::string(kMaxJsonDepth, ']');
    EXPECT_TRUE(parseJsonFast(deepest).has_value());
    EXPECT_TRUE(fastAgrees(deepest));
    const std::string tooDeep = "[" + deepest + "]";
    EXPECT_FALSE(parseJsonFast(tooDeep).has_value());
    EXPECT_NE(message(tooDeep).find("nested more than 64 levels deep"), std::string::npos);
    for (const std::string& text :
         {std::string("{\"a\": 1,}"), std::string("[1,]"), std::string("1e400"),
          std::string("{\"a\": 1} x"), std::string(""), std::string("\"\\ud800\""),
          std::string("\"a\x01b\""), std::string("\"\xff\""), std::string("[1, 2\0]", 7),
          std::string("NaN"), std::string("// c\n{}"), std::string("01")}) {
        SCOPED_TRACE(text);
        EXPECT_FALSE(parseJsonFast(text).has_value());
        EXPECT_NE(message(text), "");
    }
    EXPECT_NE(
        message("{\n  \"a\": 1,\n  \"b\": ]\n}").find("f.json: line 3, column 8: invalid JSON"),
        std::string::npos);
}

TEST(JsonParse, BundledFilesGiveTheSameDocument) {
    const std::filesystem::path root = NENRIN_SOURCE_DIR;
    int files = 0;
    for (const char* folder : {"scenes", "scenes/skeletons", "data/gran1", "share"}) {
        if (!std::filesystem::is_directory(root / folder)) continue;
        for (const auto& entry : std::filesystem::recursive_directory_iterator(root / folder)) {
            if (entry.path().extension() != ".json") continue;
            SCOPED_TRACE(entry.path().string());
            const std::string text = readFile(entry.path());
            ASSERT_TRUE(parseJsonFast(text).has_value());
            EXPECT_TRUE(fastAgrees(text));
            ++files;
        }
    }
    EXPECT_GE(files, 10);
}

TEST(JsonParse, MutatedDocumentsNeverDisagree) {
    // A deterministic fuzz of the property: bytes changed, dropped and doubled in valid
    // documents, so that most mutants are still JSON or fail late.
    const std::string seeds[] = {
        R"({"points": [[0, 0, 0], [0.1, -0.2, 1e-3]], "gamma": 0.5, "name": "a\u00e9\n",)"
        R"( "on": true, "off": null, "n": -12, "big": 18446744073709551615})",
        R"([{"a": {"b": [1, 2, {"c": "d"}]}}, [], {}, "", 0, -0.0, 1E5])",
    };
    const char alphabet[] = "{}[],:\"\\-+.eE0123456789 \n\tabcfnrstu\x00\xff\xc3\xef";
    std::mt19937 random(20261203);
    int checked = 0, fastTook = 0;
    for (const std::string& seed : seeds) {
        for (int i = 0; i < 3000; ++i) {
            std::string text = seed;
            const int edits = 1 + static_cast<int>(random() % 3);
            for (int e = 0; e < edits && !text.empty(); ++e) {
                const size_t at = random() % text.size();
                const char c = alphabet[random() % (sizeof alphabet - 1)];
                switch (random() % 3) {
                    case 0:
                        text[at] = c;
                        break;
                    case 1:
                        text.erase(at, 1);
                        break;
                    default:
                        text.insert(at, 1, c);
                        break;
                }
            }
            ASSERT_TRUE(fastAgrees(text)) << text;
            fastTook += parseJsonFast(text).has_value();
            ++checked;
        }
    }
    // Both outcomes were exercised.
    EXPECT_GT(fastTook, checked / 50);
    EXPECT_LT(fastTook, checked);
}

}  // namespace
}  // namespace nenrin
