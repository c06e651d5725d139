#pragma once
/// `nenrin farm slurm [options] COMMAND...`: writes (and submits) the SLURM job that runs a
/// render or bake split into --tiles parts plus their merge, or the frames of a batch file,
/// on a cluster (docs/farm.md).

#include <CLI/CLI.hpp>

namespace nenrin {

void addFarmCommand(CLI::App& app);

}  // namespace nenrin
