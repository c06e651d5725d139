#include "util/input_file.h"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>

#include "util/input_error.h"
#include "util/memory_budget.h"

namespace nenrin {

std::string readInputFile(const std::string& path, uintmax_t maxBytes, const std::string& what,
                          size_t spareBytes) {
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (std::filesystem::is_directory(status))
        throw InputError(path, "", "this is a folder: expected " + what);
    if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
        throw InputError(path, "", "not a regular file (a device or a FIFO?): expected " + what);
    const auto tooLarge = [&](uintmax_t size) {
        return InputError(
            path, "",
            fmt::format("{}: larger than the {} nenrin reads as {}", formatBytes(double(size)),
                        formatBytes(double(maxBytes)), what));
    };
    uintmax_t expected = 0;
    if (std::filesystem::is_regular_file(status)) {
        uintmax_t size = std::filesystem::file_size(path, ec);
        if (!ec && size > maxBytes) throw tooLarge(size);
        if (!ec) expected = size;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, "", "cannot open the file for reading (does it exist?)");
    std::string bytes;
    bytes.reserve(static_cast<size_t>(expected) + spareBytes);
    char buffer[1 << 16];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
        bytes.append(buffer, static_cast<size_t>(in.gcount()));
        if (bytes.size() > maxBytes) throw tooLarge(bytes.size());
    }
    if (in.bad()) throw InputError(path, "", "cannot read the file");
    if (bytes.capacity() < bytes.size() + spareBytes) bytes.reserve(bytes.size() + spareBytes);
    return bytes;
}

}  // namespace nenrin
