#pragma once
/// Shared pieces of the fuzz targets.
///
/// The readers take paths, so every target writes the fuzzer's bytes to a file first: the whole
/// reading path runs, size and file-type checks included. A reader may answer bad bytes only
/// with an InputError; any other exception escapes and libFuzzer reports it as a crash, as it
/// does sanitizer reports, timeouts and allocations past -malloc_limit_mb.

#include <cstddef>
#include <cstdint>
#include <string>

namespace nenrin::fuzz {

/// Writes the input to a file of this process (one per extension, reused across runs) in a
/// folder that lives as long as the process, and returns its path.
std::string writeInputFile(const uint8_t* data, size_t size, const std::string& extension);

/// The folder writeInputFile writes into; a target may put other files beside its input.
const std::string& inputFolder();

/// Reports a broken invariant (a non-finite value in an output) and aborts, so libFuzzer
/// records the input.
[[noreturn]] void fail(const std::string& what);

}  // namespace nenrin::fuzz
