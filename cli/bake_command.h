#pragma once
/// `nenrin bake slice` and `nenrin bake volume`.

#include <CLI/CLI.hpp>

namespace nenrin {

void addBakeCommands(CLI::App& app);

}  // namespace nenrin
