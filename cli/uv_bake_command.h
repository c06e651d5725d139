#pragma once
/// `nenrin bake uv --scene SCENE.json --object NAME --res 2048 -o DIR/`.

#include <CLI/CLI.hpp>

namespace nenrin {

void addUvBakeCommand(CLI::App* bake);

}  // namespace nenrin
