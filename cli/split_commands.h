#pragma once
/// Commands for jobs bigger than one process (docs/farm.md):
///   nenrin merge PARTS... -o OUT [--png PNG]     the parts of a --tile K/N job, as one file
///   nenrin batch FILE [--frame I | --list]       the frames of a batch file
///   nenrin farm slurm ...                         SLURM job scripts for both (farm_command)

#include <CLI/CLI.hpp>

namespace nenrin {

void addMergeCommand(CLI::App& app);
void addBatchCommand(CLI::App& app);

}  // namespace nenrin
