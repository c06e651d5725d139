#pragma once
/// `nenrin pov SCENE.json -o DIR/` and `nenrin compare A.exr B.exr [--diff D.exr]`.

#include <CLI/CLI.hpp>

namespace nenrin {

void addPovCommands(CLI::App& app);

}  // namespace nenrin
