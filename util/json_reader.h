#pragma once
/// Typed, strict reading of nenrin's JSON files (skeletons, grain parameters, scenes).
///
/// Every value is read through a JsonReader that knows the file name and the JSON path of the
/// object it wraps, remembers which keys were read, and turns every problem into an InputError
/// naming the file, the path (`branches[2].gamma`) and what was expected. finish() rejects keys
/// that were never read, so a misspelled parameter is an error instead of a silent default.

#include <cstdint>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "util/input_error.h"
#include "util/json_parse.h"
#include "util/vec3.h"

namespace nenrin {

/// The largest magnitude of any real number in a nenrin JSON file.
inline constexpr double kMaxJsonMagnitude = 1e9;

/// A path written in the JSON file `file`: absolute as it is, else relative to the file's folder.
std::string pathRelativeTo(const std::string& file, const std::string& path);

/// "a number", "a string", ... for messages such as "expected an object, found a string".
const char* jsonTypeName(const nlohmann::json& value);

class JsonReader {
public:
    /// `node` must outlive the reader. `path` is the JSON path of `node` ("" for the root).
    JsonReader(const nlohmann::json& node, std::string file, std::string path = "");

    bool has(const std::string& key) const;
    /// True if the key is present and holds a number / a boolean (for keys that take either).
    bool isNumber(const std::string& key) const;
    bool isBoolean(const std::string& key) const;
    const std::string& file() const { return file_; }
    const std::string& path() const { return path_; }
    /// The JSON path of a key of this object, e.g. "branches[2].gamma".
    std::string pathOf(const std::string& key) const;
    /// An InputError located at `key` of this object (or at the object itself if key is empty).
    InputError error(const std::string& key, const std::string& message) const;

    double number(const std::string& key, double fallback);
    double requireNumber(const std::string& key);
    /// A finite number > 0.
    double positive(const std::string& key, double fallback);
    double requirePositive(const std::string& key);
    /// A finite number >= 0.
    double nonNegative(const std::string& key, double fallback);
    /// A finite number in [lo, hi].
    double inRange(const std::string& key, double fallback, double lo, double hi);
    /// A finite number >= minimum, the smallest value that makes physical sense; `meaning`
    /// says what the minimum is in words for the message ("m/year: 0.1 mm a year, ..."). Speeds,
    /// widths and wavelengths below such a minimum overflow the growth field (1e-308 once
    /// crashed it), so every one has its minimum.
    double atLeast(const std::string& key, double fallback, double minimum,
                   const std::string& meaning);
    /// 0 (a default the file leaves to nenrin) or atLeast(key, ..., minimum, meaning).
    double zeroOrAtLeast(const std::string& key, double fallback, double minimum,
                         const std::string& meaning);
    long long integer(const std::string& key, long long fallback, long long lo, long long hi);
    bool boolean(const std::string& key, bool fallback);
    std::string string(const std::string& key, const std::string& fallback);
    std::string choice(const std::string& key, const std::string& fallback,
                       std::initializer_list<const char*> options);
    Vec3 vec3(const std::string& key, const Vec3& fallback);
    Vec3 requireVec3(const std::string& key);
    std::vector<Vec3> requireVec3List(const std::string& key);
    std::vector<double> numberList(const std::string& key);

    /// Any JSON value under `key`, marked as read (nullptr if absent): for values nenrin
    /// passes on rather than reads (scene overrides).
    const nlohmann::json* raw(const std::string& key);
    /// The object under `key`, or nullopt if absent. Call finish() on it as well.
    std::optional<JsonReader> object(const std::string& key);
    /// The array of objects under `key` (empty if absent).
    std::vector<JsonReader> objectList(const std::string& key);

    /// Throws if the object holds a key that was never read.
    void finish() const;

private:
    const nlohmann::json& at(const std::string& key);
    /// The value as a number, or an error naming `where` (called only on a bad value: paths are
    /// built only for messages, as a skeleton file has hundreds of thousands of numbers).
    double toNumber(const nlohmann::json& v, const std::string& where) const;
    Vec3 toVec3(const nlohmann::json& v, const std::string& where) const;
    template <class Where>
    double readNumber(const nlohmann::json& v, const Where& where) const;
    template <class Where>
    Vec3 readVec3(const nlohmann::json& v, const Where& where) const;

    const nlohmann::json* node_;
    std::string file_;
    std::string path_;
    /// The values read so far (each a member of node_): finish() names any other key.
    std::vector<const nlohmann::json*> used_;
};

}  // namespace nenrin
