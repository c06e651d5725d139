#include "renderer/finite_output.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace nenrin {

void requireFiniteOutput(const float* values, size_t count,
                         const std::vector<std::string>& channels, int width, int firstRow,
                         const std::string& path) {
    for (size_t i = 0; i < count; ++i) {
        if (std::isfinite(values[i])) continue;
        const size_t sample = i / channels.size();
        throw std::runtime_error(fmt::format(
            "{}: sample ({}, {}), channel {} is {}: nenrin computed a non-finite value (a bug; "
            "please report it with the inputs), so nothing was written",
            path, sample % size_t(width), firstRow + sample / size_t(width),
            channels[i % channels.size()], values[i]));
    }
}

}  // namespace nenrin
