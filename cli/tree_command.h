#pragma once
/// `nenrin tree ...`: skeleton sources. `tree import FILE -o tree.json` for measured trees
/// (Gran_1 CT logs, TreeQSM cylinder lists, Hayashi measured-branch files), `tree preview
/// tree.json -o tree.png`, and one subcommand per tree model (cli/tree_model_commands.cpp).

#include <CLI/CLI.hpp>

namespace nenrin {

/// Adds the `tree` command group and returns it (the model commands attach to it).
CLI::App* addTreeCommands(CLI::App& app);

}  // namespace nenrin
