#include "util/content_hash.h"

#include <fmt/format.h>

#include <cstdint>
#include <fstream>
#include <new>
#include <vector>

#include "util/input_error.h"

namespace nenrin {

ContentHash::ContentHash() : state_(XXH3_createState()) {
    if (!state_ || XXH3_128bits_reset(state_) != XXH_OK) throw std::bad_alloc();
}

ContentHash::~ContentHash() { XXH3_freeState(state_); }

void ContentHash::add(std::string_view text) {
    const uint64_t size = text.size();
    XXH3_128bits_update(state_, &size, sizeof size);
    XXH3_128bits_update(state_, text.data(), text.size());
}

void ContentHash::addFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, "", "cannot open the file to fingerprint it");
    std::vector<char> buffer(1 << 16);
    uint64_t total = 0;
    while (in) {
        in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
        const auto n = static_cast<size_t>(in.gcount());
        XXH3_128bits_update(state_, buffer.data(), n);
        total += n;
    }
    if (in.bad()) throw InputError(path, "", "read error while fingerprinting the file");
    XXH3_128bits_update(state_, &total, sizeof total);
}

std::string ContentHash::hex() const {
    const XXH128_hash_t h = XXH3_128bits_digest(state_);
    return fmt::format("{:016x}{:016x}", h.high64, h.low64);
}

}  // namespace nenrin
