#pragma once
#include <CLI/CLI.hpp>

namespace nenrin {

/// `nenrin fit SAMPLE.json -o DIR`: a skeleton and grain file from photographs of a sample
/// (docs/fit.md).
void addFitCommand(CLI::App& app);

}  // namespace nenrin
