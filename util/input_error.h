#pragma once
/// The one exception type for bad user input: it names the file, the place in it (a JSON path
/// such as `branches[3].gamma`, or `line 4, column 7` for syntax errors) and what was expected.
/// Library code throws it; the CLI catches it once, prints what() on one line and exits non-zero.

#include <stdexcept>
#include <string>

namespace nenrin {

class InputError : public std::runtime_error {
public:
    InputError(std::string file, std::string where, std::string message);

    const std::string& file() const { return file_; }
    const std::string& where() const { return where_; }
    const std::string& message() const { return message_; }

private:
    std::string file_, where_, message_;
};

/// A library's message (OCIO's YAML errors, tinyobjloader's, tinygltf's) on one line: line
/// breaks become spaces, runs of spaces one, no trailing space. InputError prints one line.
std::string oneLine(std::string message);

}  // namespace nenrin
