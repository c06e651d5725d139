#include "renderer/finite_output.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace nenrin {

namespace {

[[noreturn]] void reportNonFinite(float value, size_t sample, const std::string& channel, int width,
                                  int firstRow, const std::string& path) {
    throw std::runtime_error(fmt::format(
        "{}: sample ({}, {}), channel {} is {}: nenrin computed a non-finite value (a bug; "
        "please report it with the inputs), so nothing was written",
        path, sample % size_t(width), firstRow + sample / size_t(width), channel, value));
}

}  // namespace

void requireFiniteOutput(const float* values, size_t count,
                         const std::vector<std::string>& channels, int width, int firstRow,
                         const std::string& path) {
    for (size_t i = 0; i < count; ++i)
        if (!std::isfinite(values[i]))
            reportNonFinite(values[i], i / channels.size(), channels[i % channels.size()], width,
                            firstRow, path);
}

void requireFiniteChannel(const float* values, size_t stride, size_t pixels,
                          const std::string& channel, int width, int firstRow,
                          const std::string& path) {
    for (size_t i = 0; i < pixels; ++i)
        if (!std::isfinite(values[i * stride]))
            reportNonFinite(values[i * stride], i, channel, width, firstRow, path);
}

}  // namespace nenrin
