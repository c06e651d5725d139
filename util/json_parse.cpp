#include "util/json_parse.h"

#include <fmt/format.h>
#include <simdjson.h>

#include <algorithm>
#include <cstring>
#include <set>
#include <vector>

#include "util/input_error.h"
#include "util/input_file.h"

namespace nenrin {

namespace {

std::string lineColumn(const std::string& text, size_t offset) {
    size_t line = 1, column = 1;
    for (size_t i = 0; i < offset && i < text.size(); ++i) {
        if (text[i] == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
    }
    return fmt::format("line {}, column {}", line, column);
}

/// Finds where nlohmann's parser gives up, for errors that do not carry a position (a number
/// too large for a double): a SAX pass that stops at the first error and keeps its offset.
struct ErrorLocator : nlohmann::json_sax<nlohmann::json> {
    size_t offset = 0;
    bool null() override { return true; }
    bool boolean(bool) override { return true; }
    bool number_integer(number_integer_t) override { return true; }
    bool number_unsigned(number_unsigned_t) override { return true; }
    bool number_float(number_float_t, const string_t&) override { return true; }
    bool string(string_t&) override { return true; }
    bool binary(binary_t&) override { return true; }
    bool start_object(std::size_t) override { return true; }
    bool key(string_t&) override { return true; }
    bool end_object() override { return true; }
    bool start_array(std::size_t) override { return true; }
    bool end_array() override { return true; }
    bool parse_error(std::size_t position, const std::string&,
                     const nlohmann::detail::exception&) override {
        offset = position;
        return false;
    }
};

/// What a strict reader refuses that nlohmann's parser accepts: a key twice in one object (the
/// last would silently win, hiding a bad value), and nesting deeper than kMaxJsonDepth (deep
/// documents overflow the stack of recursive readers). Checked by the parser's callback during
/// the one parse, keeping the JSON path for the message.
class StrictnessCheck {
public:
    explicit StrictnessCheck(std::string name) : name_(std::move(name)) {}

    bool operator()(int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
        using Event = nlohmann::json::parse_event_t;
        switch (event) {
            case Event::object_start:
            case Event::array_start:
                if (levels_.size() >= kMaxJsonDepth) {
                    std::string where = path();
                    if (where.size() > 100) where = "..." + where.substr(where.size() - 100);
                    throw InputError(name_, where,
                                     fmt::format("nested more than {} levels deep", kMaxJsonDepth));
                }
                levels_.push_back({event == Event::object_start, {}, "", 0});
                break;
            case Event::key: {
                Level& l = levels_.back();
                l.key = parsed.get<std::string>();
                if (!l.keys.insert(l.key).second)
                    throw InputError(name_, path(),
                                     fmt::format("\"{}\" a second time in this object (the last "
                                                 "would silently win)",
                                                 l.key));
                break;
            }
            case Event::object_end:
            case Event::array_end:
                levels_.pop_back();
                countValue();
                break;
            case Event::value:
                countValue();
                break;
        }
        return true;
    }

private:
    struct Level {
        bool object;
        std::set<std::string> keys;
        std::string key;
        size_t index = 0;
    };

    void countValue() {
        if (!levels_.empty() && !levels_.back().object) ++levels_.back().index;
    }
    std::string path() const {
        std::string p;
        for (const Level& l : levels_) {
            if (l.object) {
                if (!l.key.empty()) p += (p.empty() ? "" : ".") + l.key;
            } else {
                p += fmt::format("[{}]", l.index);
            }
        }
        return p.empty() ? "(top level)" : p;
    }

    std::string name_;
    std::vector<Level> levels_;
};

/// The simdjson document as nlohmann's parser would have built it, or false where the strict
/// reader must refuse it (a key twice in one object, nesting deeper than kMaxJsonDepth): the
/// caller then lets nlohmann's parser say where. `depth`: the containers around `e`.
bool convert(simdjson::dom::element e, nlohmann::json& out, size_t depth) {
    using Type = simdjson::dom::element_type;
    switch (e.type()) {
        case Type::OBJECT: {
            if (depth >= kMaxJsonDepth) return false;
            out = nlohmann::json::object();
            auto& members = *out.get_ptr<nlohmann::json::object_t*>();
            for (const simdjson::dom::key_value_pair member : simdjson::dom::object(e)) {
                auto [it, inserted] = members.emplace(std::string(member.key), nullptr);
                if (!inserted || !convert(member.value, it->second, depth + 1)) return false;
            }
            return true;
        }
        case Type::ARRAY: {
            if (depth >= kMaxJsonDepth) return false;
            out = nlohmann::json::array();
            auto& items = *out.get_ptr<nlohmann::json::array_t*>();
            const simdjson::dom::array array(e);
            items.reserve(array.size());
            for (const simdjson::dom::element item : array) {
                items.emplace_back();
                if (!convert(item, items.back(), depth + 1)) return false;
            }
            return true;
        }
        // nlohmann keeps integers written without a sign as unsigned. ("-0" is the one
        // difference: nlohmann's signed 0 comes back as an unsigned 0. Same value, same
        // dump, and is_number_integer() is true for both.)
        case Type::INT64: {
            const int64_t v = int64_t(e);
            if (v >= 0)
                out = static_cast<nlohmann::json::number_unsigned_t>(v);
            else
                out = static_cast<nlohmann::json::number_integer_t>(v);
            return true;
        }
        case Type::UINT64:
            out = static_cast<nlohmann::json::number_unsigned_t>(uint64_t(e));
            return true;
        case Type::DOUBLE:
            out = double(e);
            return true;
        case Type::STRING:
            out = std::string(std::string_view(e));
            return true;
        case Type::BOOL:
            out = bool(e);
            return true;
        case Type::NULL_VALUE:
            out = nullptr;
            return true;
    }
    return false;
}

}  // namespace

std::optional<nlohmann::json> parseJsonFast(const std::string& text) {
    // Numbers simdjson refuses but nlohmann takes (integers past 64 bits become doubles
    // there), a byte-order mark, anything malformed: all go the careful way.
    if (text.find('\0') != std::string::npos) return std::nullopt;
    simdjson::dom::parser parser;
    simdjson::dom::element root;
    if (parser.parse(text).get(root) != simdjson::SUCCESS) return std::nullopt;
    nlohmann::json out;
    if (!convert(root, out, 0)) return std::nullopt;
    return out;
}

nlohmann::json parseJsonReportingErrors(const std::string& text, const std::string& name) {
    if (size_t nul = text.find('\0'); nul != std::string::npos)
        throw InputError(name, lineColumn(text, nul), "a NUL byte: expected JSON text");
    try {
        return nlohmann::json::parse(text, StrictnessCheck(name));
    } catch (const nlohmann::json::out_of_range& e) {
        ErrorLocator locator;
        nlohmann::json::sax_parse(text, &locator);
        std::string what = e.what();
        auto q0 = what.find('\''), q1 = what.rfind('\'');
        std::string token = q0 != std::string::npos && q1 > q0 ? what.substr(q0 + 1, q1 - q0 - 1)
                                                               : std::string("number");
        // The SAX position is just past the number: report where the number starts.
        size_t start = locator.offset >= token.size() ? locator.offset - token.size() : 0;
        throw InputError(name, lineColumn(text, start),
                         "number out of range (" + token + "): expected a finite number");
    } catch (const nlohmann::json::parse_error& e) {
        // e.byte is the 1-based offset of the offending character; turn it into line:column.
        size_t end = std::min<size_t>(e.byte == 0 ? 0 : e.byte - 1, text.size());
        // nlohmann says "[json.exception.parse_error.101] parse error at line 1, column 2:
        // syntax error while parsing ...": keep what follows the position.
        std::string what = e.what();
        auto at = what.find("parse error");
        auto colon = at == std::string::npos ? std::string::npos : what.find(": ", at);
        std::string detail = colon != std::string::npos ? what.substr(colon + 2) : what;
        if (end >= text.size()) detail = "unexpected end of file (truncated JSON?): " + detail;
        throw InputError(name, lineColumn(text, end), "invalid JSON: " + detail);
    }
}

std::string jsonDifference(const nlohmann::json& a, const nlohmann::json& b) {
    struct Compare {
        std::string operator()(const nlohmann::json& a, const nlohmann::json& b,
                               const std::string& where) const {
            auto differ = [&](const char* what) {
                return fmt::format("{}: {}: {} vs {}", where.empty() ? "(top level)" : where, what,
                                   a.dump(), b.dump());
            };
            const bool zeros = a.is_number_integer() && b.is_number_integer() &&
                               a.get<long long>() == 0 && b.get<long long>() == 0;
            if (a.type() != b.type() && !zeros) return differ("types differ");
            if (a.is_object() || a.is_array()) {
                if (a.size() != b.size()) return differ("sizes differ");
                size_t index = 0;
                for (auto i = a.begin(), j = b.begin(); i != a.end(); ++i, ++j, ++index) {
                    if (a.is_object() && i.key() != j.key()) return differ("keys differ");
                    const std::string inner = a.is_object()
                                                  ? (where.empty() ? "" : where + ".") + i.key()
                                                  : fmt::format("{}[{}]", where, index);
                    if (std::string d = (*this)(*i, *j, inner); !d.empty()) return d;
                }
                return "";
            }
            if (a.is_number_float()) {
                const double x = a.get<double>(), y = b.get<double>();
                return std::memcmp(&x, &y, sizeof x) == 0 ? "" : differ("float bits differ");
            }
            return a == b ? "" : differ("values differ");
        }
    };
    return Compare{}(a, b, "");
}

nlohmann::json parseJsonText(const std::string& text, const std::string& name) {
    if (auto parsed = parseJsonFast(text)) return std::move(*parsed);
    return parseJsonReportingErrors(text, name);
}

nlohmann::json parseJsonFile(const std::string& path) {
    return parseJsonText(
        readInputFile(path, kMaxJsonFileBytes, "a JSON file", simdjson::SIMDJSON_PADDING), path);
}

}  // namespace nenrin
