#pragma once
/// `nenrin render SCENE.json -o out.exr [--spp N] [--res WxH] [--threads N] [--seed S]
/// [--png out.png] [--quiet]`.

#include <CLI/CLI.hpp>

namespace nenrin {

void addRenderCommand(CLI::App& app);

}  // namespace nenrin
