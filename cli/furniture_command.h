#pragma once
/// `nenrin furniture MODEL --grain G.json -o DIR [--skeleton S.json] [--unit mm|cm|m]
/// [--plan PLAN.json] [--res N]`: a whole piece of furniture in solid wood (docs/furniture.md).

#include <CLI/CLI.hpp>

namespace nenrin {

void addFurnitureCommand(CLI::App& app);

}  // namespace nenrin
