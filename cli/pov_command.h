#pragma once
/// `nenrin pov SCENE.json -o DIR/`.

#include <CLI/CLI.hpp>

namespace nenrin {

void addPovCommands(CLI::App& app);

}  // namespace nenrin
