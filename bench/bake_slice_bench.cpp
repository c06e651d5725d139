// Slice bake benchmark (issue 30): a 5 cm flat-sawn face of the hinoki preset (the look the
// photographs are held to: wander, speckle, streaks, ring tones, end-grain term), 8 cm off the
// pith of a straight trunk, as `nenrin bake slice --origin/--right/--up` bakes it, at 512 x 512
// on 1 and 2 threads. BM_BakeSlice/<resolution>/<threads>; also the same face with the anatomy
// off (BM_BakeSliceAnatomyOff), what the look costs. Counter: samples/s.

#include <benchmark/benchmark.h>

#include <string>

#include "grain/grown_tree.h"
#include "renderer/bake/bake_specs.h"
#include "renderer/bake/grid_bake.h"
#include "skeleton/skeleton_file.h"

namespace nenrin {
namespace {

void bakeSlice(benchmark::State& state, bool anatomy) {
    const std::string source = NENRIN_SOURCE_DIR;
    GrainParams grain = loadGrainFile(source + "/scenes/grain/species/hinoki.json");
    grain.anatomy.enabled = anatomy;
    GrownTree grown(loadSkeletonFile(source + "/scenes/skeletons/straight-trunk.json"), grain);
    const WoodShader shader(grown.field());
    SliceSpec spec;
    spec.cut = PlaneCut{{0.08, -0.025, 0.975}, {0, 0.05, 0}, {0, 0, 0.05}};
    spec.resX = spec.resY = static_cast<int>(state.range(0));
    BakeOptions options;
    options.threads = static_cast<int>(state.range(1));
    options.quiet = true;
    for (auto _ : state) {
        BakedGrid grid = sliceGrid(grown.skeleton(), spec);
        bakeGrid(shader, grid, options);
        benchmark::DoNotOptimize(grid.data.data());
    }
    state.counters["samples/s"] = benchmark::Counter(
        double(spec.resX) * spec.resY * state.iterations(), benchmark::Counter::kIsRate);
}

void BM_BakeSlice(benchmark::State& state) { bakeSlice(state, true); }
void BM_BakeSliceAnatomyOff(benchmark::State& state) { bakeSlice(state, false); }

BENCHMARK(BM_BakeSlice)
    ->Args({512, 1})
    ->Args({512, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BakeSliceAnatomyOff)->Args({512, 1})->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace nenrin
