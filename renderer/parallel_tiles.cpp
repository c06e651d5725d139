#include "renderer/parallel_tiles.h"

#include <pmmintrin.h>
#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <xmmintrin.h>

#include <algorithm>

namespace nenrin {

int workerThreads(int threads) {
    // More threads than cores cannot run (TBB would print a warning through -q).
    const int cores = tbb::info::default_concurrency();
    return threads > 0 ? std::min(threads, cores) : cores;
}

void parallelTiles(size_t tileCount, int threads, const std::function<void(size_t)>& body) {
    // The result does not depend on the count.
    tbb::task_arena arena(workerThreads(threads));
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, tileCount, 1),
                          [&](const tbb::blocked_range<size_t>& r) {
                              _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
                              _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
                              for (size_t t = r.begin(); t != r.end(); ++t) body(t);
                          });
    });
}

}  // namespace nenrin
