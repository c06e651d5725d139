#pragma once
/// `nenrin grain strip PHOTO -o grain.json [--grain base.json]`: a ring colour profile measured
/// from a photographed strip (pith on the left, bark on the right; docs/grain-format.md,
/// "Colours from a photograph") written as grain colour keys, so renders match the user's
/// own timber.

#include <CLI/CLI.hpp>

namespace nenrin {

void addGrainCommands(CLI::App& app);

}  // namespace nenrin
