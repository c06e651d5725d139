#pragma once
/// Reading a user's input file whole, safely: a folder, a device, a FIFO or a socket is refused
/// before it is opened (/dev/zero as an input once grew to 16 GB), and so is a file larger than
/// the reader's limit, also if it grows while being read. Every refusal is an InputError
/// naming the file and what was expected.

#include <cstdint>
#include <string>

namespace nenrin {

/// The whole file as bytes. `what` is what the reader expected, e.g. "a JSON file" or "an
/// OBJ file"; `maxBytes` the largest file it takes. The string's capacity has at least
/// `spareBytes` to spare past the contents: parsers that read past the end in blocks
/// (simdjson) then need no padded copy.
std::string readInputFile(const std::string& path, uintmax_t maxBytes, const std::string& what,
                          size_t spareBytes = 0);

}  // namespace nenrin
