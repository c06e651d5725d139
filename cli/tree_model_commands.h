#pragma once
/// The tree models as `nenrin tree MODEL` subcommands (hayashi, akagi, kanayama) and the
/// forest stand as `nenrin stand kunii|fell`. Each writes a skeleton (or stand) file; see
/// docs/trees.md.

#include <CLI/CLI.hpp>

namespace nenrin {

void addTreeModelCommands(CLI::App& tree);
void addStandCommands(CLI::App& app);

}  // namespace nenrin
