#pragma once
/// `nenrin tree rings FILE.rwl`: measured ring-width series (Tucson .rwl, docs/ring-series.md).
/// `--list` prints each series; `--series ID --skeleton S.json -o OUT.json [--mean-width MM]`
/// writes S with that series as its yearly `ring_widths`.

#include <CLI/CLI.hpp>

namespace nenrin {

void addRingSeriesCommand(CLI::App& tree);

}  // namespace nenrin
