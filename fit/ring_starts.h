#pragma once
/// Where rings begin along a lightness profile across them whose period is known: each ring
/// starts with its sharpest change, where the dense late wood of the last year meets this
/// year's early wood (a conifer's pale early wood after a dark late-wood line: a rise; a
/// ring-porous hardwood's dark band of large pores after pale late wood: a fall). Which of the
/// two a profile shows, and whether its period is the rings' or their texture's, is read from
/// it: the chain of edges scoring best (strong edges, gaps near one period).

#include <vector>

namespace nenrin {

/// Indexes into `lightness` (samples outward) where a ring starts, increasing.
/// `samplesPerPeriod`: the period its swings count, which may be half the rings'; the starts'
/// gaps lie near 0.7-3 times it, no two closer than a third of it.
std::vector<int> ringStarts(const std::vector<double>& lightness, double samplesPerPeriod);

}  // namespace nenrin
