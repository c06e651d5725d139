#include "util/memory_budget.h"

#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "util/input_error.h"

namespace nenrin {

namespace {

std::atomic<uint64_t> limitBytes{0};  // 0 = the default

}  // namespace

uint64_t availableMemoryBytes() {
    long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
    uint64_t bytes =
        pages > 0 && pageSize > 0 ? uint64_t(pages) * uint64_t(pageSize) : uint64_t(4) << 30;
    // cgroup v2: "max" or a byte count.
    std::ifstream cgroup("/sys/fs/cgroup/memory.max");
    std::string text;
    if (cgroup >> text && !text.empty() && std::isdigit(static_cast<unsigned char>(text[0]))) {
        uint64_t cap = std::strtoull(text.c_str(), nullptr, 10);
        if (cap > 0 && cap < bytes) bytes = cap;
    }
    return bytes;
}

uint64_t memoryLimit() {
    uint64_t set = limitBytes.load();
    return set ? set : availableMemoryBytes() / 5 * 4;
}

void setMemoryLimit(uint64_t bytes) { limitBytes.store(bytes); }

std::string formatBytes(double bytes) {
    if (bytes >= double(uint64_t(1) << 40))
        return fmt::format("{:.1f} TiB", bytes / double(uint64_t(1) << 40));
    if (bytes >= double(1 << 30)) return fmt::format("{:.1f} GiB", bytes / double(1 << 30));
    if (bytes >= double(1 << 20)) return fmt::format("{:.0f} MiB", bytes / double(1 << 20));
    return fmt::format("{:.0f} KiB", std::ceil(bytes / 1024));
}

uint64_t parseByteSize(const std::string& text) {
    char* end = nullptr;
    double value = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || !std::isfinite(value) || value <= 0) return 0;
    std::string unit(end);
    for (char& c : unit) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    double scale = 0;
    if (unit.empty() || unit == "B")
        scale = 1;
    else if (unit == "K" || unit == "KB" || unit == "KIB")
        scale = 1024.0;
    else if (unit == "M" || unit == "MB" || unit == "MIB")
        scale = 1024.0 * 1024;
    else if (unit == "G" || unit == "GB" || unit == "GIB")
        scale = 1024.0 * 1024 * 1024;
    else if (unit == "T" || unit == "TB" || unit == "TIB")
        scale = 1024.0 * 1024 * 1024 * 1024;
    double bytes = value * scale;
    if (scale == 0 || bytes < 1 || bytes > 1e18) return 0;
    return static_cast<uint64_t>(bytes);
}

void requireMemory(double bytes, const std::string& what, const std::string& source) {
    const uint64_t limit = memoryLimit();
    if (bytes <= double(limit)) return;
    const std::string whose = limitBytes.load()
                                  ? std::string("the --max-memory limit")
                                  : fmt::format(
                                        "the memory limit (80 % of this machine's {}; "
                                        "--max-memory changes it)",
                                        formatBytes(double(availableMemoryBytes())));
    throw InputError(source, "",
                     fmt::format("{} needs about {}, over {} of {}", what, formatBytes(bytes),
                                 whose, formatBytes(double(limit))));
}

void requireOutputSpace(double bytes, const std::string& what, const std::string& folder) {
    requireMemory(bytes, what, folder);
    std::error_code ec;
    const std::filesystem::space_info space = std::filesystem::space(folder, ec);
    if (!ec && bytes > double(space.available))
        throw InputError(folder, "",
                         fmt::format("{} needs about {}, but the disk has {} free", what,
                                     formatBytes(bytes), formatBytes(double(space.available))));
}

}  // namespace nenrin
