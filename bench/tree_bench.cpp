// Tree models: generation and fitting speed (issues 5 and 6). Each model adds its benchmarks in
// its own file of this binary (bench/CMakeLists.txt, nenrin_tree_bench).
#include <benchmark/benchmark.h>

#include "skeleton/skeleton_writer.h"
#include "skeleton/synthetic_tree.h"

namespace {

// Writing a generated tree to its JSON form: a baseline for the generators' own figures.
void BM_SkeletonToJson(benchmark::State& state) {
    nenrin::SyntheticTreeOptions o;
    o.totalSegments = static_cast<size_t>(state.range(0));
    nenrin::Skeleton tree = nenrin::makeSyntheticTree(o);
    for (auto _ : state) benchmark::DoNotOptimize(nenrin::skeletonToJson(tree, {}).size());
}
BENCHMARK(BM_SkeletonToJson)->Arg(10000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
