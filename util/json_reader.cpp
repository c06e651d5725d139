#include "util/json_reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

namespace nenrin {

std::string pathRelativeTo(const std::string& file, const std::string& path) {
    const std::filesystem::path p(path);
    if (p.is_absolute()) return path;
    return (std::filesystem::path(file).parent_path() / p).lexically_normal().string();
}

const char* jsonTypeName(const nlohmann::json& v) {
    if (v.is_number()) return "a number";
    if (v.is_string()) return "a string";
    if (v.is_boolean()) return "a boolean";
    if (v.is_array()) return "an array";
    if (v.is_object()) return "an object";
    return "null";
}

JsonReader::JsonReader(const nlohmann::json& node, std::string file, std::string path)
    : node_(&node), file_(std::move(file)), path_(std::move(path)) {
    if (!node_->is_object())
        throw InputError(file_, path_.empty() ? "(top level)" : path_,
                         fmt::format("expected an object, found {}", jsonTypeName(*node_)));
}

bool JsonReader::has(const std::string& key) const { return node_->contains(key); }
bool JsonReader::isNumber(const std::string& key) const {
    return has(key) && (*node_)[key].is_number();
}
bool JsonReader::isBoolean(const std::string& key) const {
    return has(key) && (*node_)[key].is_boolean();
}

std::string JsonReader::pathOf(const std::string& key) const {
    if (key.empty()) return path_.empty() ? "(top level)" : path_;
    return path_.empty() ? key : path_ + "." + key;
}

InputError JsonReader::error(const std::string& key, const std::string& message) const {
    return InputError(file_, pathOf(key), message);
}

const nlohmann::json& JsonReader::at(const std::string& key) {
    const nlohmann::json& v = (*node_)[key];
    if (std::find(used_.begin(), used_.end(), &v) == used_.end()) used_.push_back(&v);
    return v;
}

namespace {
/// What toNumber accepts, checked without a path to name.
bool acceptableNumber(const nlohmann::json& v) {
    if (!v.is_number()) return false;
    const double d = v.get<double>();
    return std::isfinite(d) && std::abs(d) <= kMaxJsonMagnitude;
}
}  // namespace

template <class Where>
double JsonReader::readNumber(const nlohmann::json& v, const Where& where) const {
    return acceptableNumber(v) ? v.get<double>() : toNumber(v, where());
}

template <class Where>
Vec3 JsonReader::readVec3(const nlohmann::json& v, const Where& where) const {
    if (v.is_array() && v.size() == 3 && acceptableNumber(v[0]) && acceptableNumber(v[1]) &&
        acceptableNumber(v[2]))
        return {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()};
    return toVec3(v, where());
}

double JsonReader::toNumber(const nlohmann::json& v, const std::string& where) const {
    if (!v.is_number())
        throw InputError(file_, where, fmt::format("expected a number, found {}", jsonTypeName(v)));
    double d = v.get<double>();
    if (!std::isfinite(d)) throw InputError(file_, where, "expected a finite number");
    // No length (m), time (years), speed or colour nenrin reads comes near this: larger values
    // are typos or attacks, and would overflow to infinity in the field or the renderer.
    if (std::abs(d) > kMaxJsonMagnitude)
        throw InputError(file_, where,
                         fmt::format("{:g} is beyond the +-{:g} nenrin accepts for any value", d,
                                     kMaxJsonMagnitude));
    return d;
}

Vec3 JsonReader::toVec3(const nlohmann::json& v, const std::string& where) const {
    if (!v.is_array() || v.size() != 3)
        throw InputError(
            file_, where,
            fmt::format("expected an array of 3 numbers [x, y, z], found {}",
                        v.is_array() ? fmt::format("{} elements", v.size()) : jsonTypeName(v)));
    return {toNumber(v[0], where + "[0]"), toNumber(v[1], where + "[1]"),
            toNumber(v[2], where + "[2]")};
}

double JsonReader::number(const std::string& key, double fallback) {
    return has(key) ? readNumber(at(key), [&] { return pathOf(key); }) : fallback;
}

double JsonReader::requireNumber(const std::string& key) {
    if (!has(key)) throw error(key, "missing required number");
    return number(key, 0);
}

double JsonReader::positive(const std::string& key, double fallback) {
    double v = number(key, fallback);
    if (!(v > 0)) throw error(key, fmt::format("expected a number > 0, found {}", v));
    return v;
}

double JsonReader::requirePositive(const std::string& key) {
    if (!has(key)) throw error(key, "missing required number (> 0)");
    return positive(key, 1);
}

double JsonReader::nonNegative(const std::string& key, double fallback) {
    double v = number(key, fallback);
    if (!(v >= 0)) throw error(key, fmt::format("expected a number >= 0, found {}", v));
    return v;
}

double JsonReader::inRange(const std::string& key, double fallback, double lo, double hi) {
    double v = number(key, fallback);
    if (!(v >= lo && v <= hi))
        throw error(key, fmt::format("expected a number in [{}, {}], found {}", lo, hi, v));
    return v;
}

double JsonReader::atLeast(const std::string& key, double fallback, double minimum,
                           const std::string& meaning) {
    double v = number(key, fallback);
    if (!(v >= minimum))
        throw error(key,
                    fmt::format("expected at least {:g} ({}), found {:g}", minimum, meaning, v));
    return v;
}

double JsonReader::zeroOrAtLeast(const std::string& key, double fallback, double minimum,
                                 const std::string& meaning) {
    double v = number(key, fallback);
    if (!(v == 0 || v >= minimum))
        throw error(
            key, fmt::format("expected 0 or at least {:g} ({}), found {:g}", minimum, meaning, v));
    return v;
}

long long JsonReader::integer(const std::string& key, long long fallback, long long lo,
                              long long hi) {
    if (!has(key)) return fallback;
    const auto& v = at(key);
    if (!v.is_number_integer())
        throw error(key, fmt::format("expected an integer, found {}", jsonTypeName(v)));
    long long i = v.get<long long>();
    if (i < lo || i > hi)
        throw error(key, fmt::format("expected an integer in [{}, {}], found {}", lo, hi, i));
    return i;
}

bool JsonReader::boolean(const std::string& key, bool fallback) {
    if (!has(key)) return fallback;
    const auto& v = at(key);
    if (!v.is_boolean())
        throw error(key, fmt::format("expected true or false, found {}", jsonTypeName(v)));
    return v.get<bool>();
}

std::string JsonReader::string(const std::string& key, const std::string& fallback) {
    if (!has(key)) return fallback;
    const auto& v = at(key);
    if (!v.is_string())
        throw error(key, fmt::format("expected a string, found {}", jsonTypeName(v)));
    return v.get<std::string>();
}

std::string JsonReader::choice(const std::string& key, const std::string& fallback,
                               std::initializer_list<const char*> options) {
    std::string s = string(key, fallback);
    std::string list;
    for (const char* o : options) {
        if (s == o) return s;
        list += list.empty() ? fmt::format("\"{}\"", o) : fmt::format(", \"{}\"", o);
    }
    throw error(key, fmt::format("expected one of {}, found \"{}\"", list, s));
}

Vec3 JsonReader::vec3(const std::string& key, const Vec3& fallback) {
    return has(key) ? readVec3(at(key), [&] { return pathOf(key); }) : fallback;
}

Vec3 JsonReader::requireVec3(const std::string& key) {
    if (!has(key)) throw error(key, "missing required [x, y, z]");
    return vec3(key, {});
}

std::vector<Vec3> JsonReader::requireVec3List(const std::string& key) {
    if (!has(key)) throw error(key, "missing required array of [x, y, z] points");
    const auto& v = at(key);
    if (!v.is_array())
        throw error(
            key, fmt::format("expected an array of [x, y, z] points, found {}", jsonTypeName(v)));
    std::vector<Vec3> out;
    for (size_t i = 0; i < v.size(); ++i)
        out.push_back(readVec3(v[i], [&] { return fmt::format("{}[{}]", pathOf(key), i); }));
    return out;
}

std::vector<double> JsonReader::numberList(const std::string& key) {
    if (!has(key)) return {};
    const auto& v = at(key);
    if (!v.is_array())
        throw error(key, fmt::format("expected an array of numbers, found {}", jsonTypeName(v)));
    std::vector<double> out;
    for (size_t i = 0; i < v.size(); ++i)
        out.push_back(readNumber(v[i], [&] { return fmt::format("{}[{}]", pathOf(key), i); }));
    return out;
}

std::optional<JsonReader> JsonReader::object(const std::string& key) {
    if (!has(key)) return std::nullopt;
    return JsonReader(at(key), file_, pathOf(key));
}

const nlohmann::json* JsonReader::raw(const std::string& key) {
    if (!has(key)) return nullptr;
    return &at(key);
}

std::vector<JsonReader> JsonReader::objectList(const std::string& key) {
    std::vector<JsonReader> out;
    if (!has(key)) return out;
    const auto& v = at(key);
    if (!v.is_array())
        throw error(key, fmt::format("expected an array of objects, found {}", jsonTypeName(v)));
    for (size_t i = 0; i < v.size(); ++i)
        out.emplace_back(v[i], file_, fmt::format("{}[{}]", pathOf(key), i));
    return out;
}

void JsonReader::finish() const {
    for (auto it = node_->begin(); it != node_->end(); ++it) {
        if (std::find(used_.begin(), used_.end(), &it.value()) == used_.end())
            throw InputError(file_, pathOf(it.key()),
                             "unknown key (misspelled? see the format documentation)");
    }
}

}  // namespace nenrin
