#pragma once
/// JSON text into a document, strictly: nenrin's files are read from the nlohmann::json this
/// returns (util/json_reader.h). Every problem is an InputError naming the file and the line
/// and column.
///
/// Two parsers, one answer. simdjson reads the text first (a skeleton file of 18 MB in a
/// tenth of the time nlohmann's parser takes) and its document is copied into nlohmann's;
/// whatever it refuses, and whatever the strict reader must refuse (a key twice in one
/// object, nesting too deep), is parsed again by nlohmann's parser, which accepts exactly
/// what it accepted before (a byte-order mark, integers past 64 bits as doubles) and says
/// where a problem is. The JsonParse tests and the fuzz target json_parse_fuzz check that the
/// two agree.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace nenrin {

/// Limits of nenrin's JSON reading: the deepest nesting and the largest file.
inline constexpr size_t kMaxJsonDepth = 64;
inline constexpr uintmax_t kMaxJsonFileBytes = uintmax_t(256) << 20;

/// Reads and parses a JSON file. Missing files and syntax errors (with line and column) throw
/// InputError.
nlohmann::json parseJsonFile(const std::string& path);
/// Parses JSON text; `name` stands for the file in error messages.
nlohmann::json parseJsonText(const std::string& text, const std::string& name);

/// The two halves of parseJsonText, for tests. The fast one: the document, or nullopt for
/// anything it leaves to the other (never a different document).
std::optional<nlohmann::json> parseJsonFast(const std::string& text);
/// nlohmann's parser with the strictness checks; errors name the line and column.
nlohmann::json parseJsonReportingErrors(const std::string& text, const std::string& name);
/// "" if the documents are the same in every value, type and bit (floats by their bits,
/// integers by signedness, but for a signed and an unsigned 0: "-0" above); else the first
/// difference, with its JSON path.
std::string jsonDifference(const nlohmann::json& a, const nlohmann::json& b);

}  // namespace nenrin
