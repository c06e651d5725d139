#pragma once
/// Runs work over tiles on a TBB arena of a given size. Results must not depend on which thread
/// runs a tile: callers write each tile's output to its own place.

#include <cstddef>
#include <functional>

namespace nenrin {

/// How many threads `threads` (0 = all cores) gives: at most the cores.
int workerThreads(int threads);

/// Calls body(tile) for tile in [0, tileCount) on `threads` threads (0 = all cores), with
/// flush-to-zero / denormals-are-zero set in every worker (Embree's advice).
void parallelTiles(size_t tileCount, int threads, const std::function<void(size_t)>& body);

}  // namespace nenrin
