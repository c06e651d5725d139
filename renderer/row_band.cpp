#include "renderer/row_band.h"

#include <fmt/format.h>

#include <algorithm>

#include "util/input_error.h"

namespace nenrin {

RowBand bandOfPart(int rows, int alignment, int part, int parts, const char* option) {
    const long long units = (static_cast<long long>(rows) + alignment - 1) / alignment;
    if (parts < 1 || part < 1 || part > parts)
        throw InputError("command line", option,
                         fmt::format("part {}/{}: expected K/N with 1 <= K <= N", part, parts));
    if (parts > units)
        throw InputError("command line", option,
                         fmt::format("{} parts, but the {} rows make only {} bands of {} rows: "
                                     "use at most {} parts",
                                     parts, rows, units, alignment, units));
    const long long first = (part - 1) * units / parts, last = part * units / parts;
    return {static_cast<int>(first * alignment),
            static_cast<int>(std::min<long long>(rows, last * alignment))};
}

}  // namespace nenrin
