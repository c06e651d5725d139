#pragma once
/// `nenrin stats IMAGE... [--against PHOTO] [--json]` and
/// `nenrin stats --rings PHOTO FIELD.exr [--json]`: wood-photo statistics (docs/stats.md).

#include <CLI/CLI.hpp>

namespace nenrin {

void addStatsCommand(CLI::App& app);

}  // namespace nenrin
