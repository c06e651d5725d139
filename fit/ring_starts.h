#pragma once
/// Where rings begin along a lightness profile across them whose period is known: each ring
/// starts with its sharpest change, where the dense late wood of the last year meets this
/// year's early wood (a conifer's pale early wood after a dark late-wood line: a rise; a
/// ring-porous hardwood's dark band of large pores after pale late wood: a fall). Which of the
/// two a profile shows is read from it: the stronger of its largest rises and falls.

#include <vector>

namespace nenrin {

/// Indexes into `lightness` (samples a period / `samplesPerPeriod` apart, outward) where a
/// ring starts, increasing; at most one per half period.
std::vector<int> ringStarts(const std::vector<double>& lightness, double samplesPerPeriod);

}  // namespace nenrin
