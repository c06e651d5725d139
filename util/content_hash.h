#pragma once
/// A 128-bit fingerprint of everything a job's result depends on (settings, input files), so
/// that the pieces of a split job can be checked to belong together before they are merged.
/// XXH3-128 (libxxhash): fast and well distributed; not a cryptographic hash.

#include <xxhash.h>

#include <string>
#include <string_view>

namespace nenrin {

class ContentHash {
public:
    ContentHash();
    ~ContentHash();
    ContentHash(const ContentHash&) = delete;
    ContentHash& operator=(const ContentHash&) = delete;

    /// Adds `text` and its length, so ("ab", "c") and ("a", "bc") differ.
    void add(std::string_view text);
    /// Adds the bytes of a file; throws InputError naming it if it cannot be read.
    void addFile(const std::string& path);
    /// 32 lower-case hex digits.
    std::string hex() const;

private:
    XXH3_state_t* state_;
};

}  // namespace nenrin
