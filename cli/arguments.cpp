#include "arguments.h"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "util/input_error.h"
#include "util/memory_budget.h"

namespace nenrin {

CLI::Validator finiteRange(double lo, double hi) {
    return CLI::Validator(
        [lo, hi](std::string& text) -> std::string {
            char* end = nullptr;
            const double v = std::strtod(text.c_str(), &end);
            if (end == text.c_str() || *end != '\0' || !std::isfinite(v) || v < lo || v > hi)
                return fmt::format("expected a finite number in [{:g}, {:g}], found \"{}\"", lo, hi,
                                   text.size() > 40 ? text.substr(0, 40) + "..." : text);
            return "";
        },
        fmt::format("FINITE in [{:g}, {:g}]", lo, hi));
}

void addMaxMemoryOption(CLI::App* command) {
    command
        ->add_option_function<std::string>(
            "--max-memory", [](const std::string& text) { setMemoryLimit(parseByteSize(text)); },
            fmt::format("Most memory the job may take, e.g. 8G or 512M; a larger job is refused "
                        "before it starts (default: 80 % of this machine's {})",
                        formatBytes(double(availableMemoryBytes()))))
        ->type_name("SIZE")
        ->check(CLI::Validator(
            [](std::string& text) -> std::string {
                return parseByteSize(text) ? ""
                                           : fmt::format(
                                                 "expected a size such as 8G, 512M or "
                                                 "2.5GiB, found \"{}\"",
                                                 text.substr(0, 40));
            },
            "SIZE"));
}

namespace {

InputError optionError(const std::string& option, const std::string& message) {
    return InputError("command line", option, message);
}

bool parseDouble(const std::string& s, double& out) {
    if (s.empty()) return false;
    char* end = nullptr;
    errno = 0;
    out = std::strtod(s.c_str(), &end);
    return errno == 0 && end == s.c_str() + s.size() && std::isfinite(out);
}

}  // namespace

std::pair<double, double> parseSizeMetres(const std::string& text, const std::string& option) {
    std::string t = text;
    if (!t.empty() && t.back() == 'm') t.pop_back();
    auto x = t.find('x');
    double w = 0, h = 0;
    if (x == std::string::npos || !parseDouble(t.substr(0, x), w) ||
        !parseDouble(t.substr(x + 1), h))
        throw optionError(option, fmt::format("expected WIDTHxHEIGHT in metres such as 0.4x0.3m, "
                                              "found \"{}\"",
                                              text));
    if (!(w > 0 && h > 0) || w > 1000 || h > 1000)
        throw optionError(option, fmt::format("expected sizes in (0, 1000] m, found \"{}\"", text));
    return {w, h};
}

std::pair<int, int> parseResolution(const std::string& text, const std::string& option, int cap) {
    auto x = text.find('x');
    double w = 0, h = 0;
    if (x == std::string::npos || !parseDouble(text.substr(0, x), w) ||
        !parseDouble(text.substr(x + 1), h) || w != std::floor(w) || h != std::floor(h))
        throw optionError(option,
                          fmt::format("expected WIDTHxHEIGHT in pixels such as 512x512, found "
                                      "\"{}\"",
                                      text));
    if (w < 1 || h < 1 || w > cap || h > cap)
        throw optionError(option,
                          fmt::format("expected 1 to {} pixels per side, found \"{}\"", cap, text));
    return {static_cast<int>(w), static_cast<int>(h)};
}

std::vector<double> parseNumberList(const std::string& text, const std::string& option,
                                    size_t count) {
    std::vector<double> out;
    size_t start = 0;
    while (true) {
        size_t comma = text.find(',', start);
        std::string item =
            text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        double v;
        if (!parseDouble(item, v))
            throw optionError(option, fmt::format("expected {} comma-separated finite numbers, "
                                                  "found \"{}\"",
                                                  count, text));
        out.push_back(v);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    if (out.size() != count)
        throw optionError(option, fmt::format("expected {} comma-separated numbers, found {}",
                                              count, out.size()));
    return out;
}

}  // namespace nenrin
