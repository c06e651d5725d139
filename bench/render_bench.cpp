// Render benchmarks (issue 3): the default scene (scenes/glulam-beam.json at its own
// resolution and spp) and a 512 x 512 frame filled with a box of wood at 16 spp, each on 1 and
// 2 threads; the box also with its anatomy off. Counters: rays/s (camera, bounce and shadow rays)
// and camera_rays/s; the benchmark's time is the wall time of one render.

#include <benchmark/benchmark.h>

#include <string>

#include "renderer/path_tracer.h"
#include "renderer/scene_file.h"

namespace nenrin {
namespace {

const std::string kSource = NENRIN_SOURCE_DIR;

void renderBenchmark(benchmark::State& state, const std::string& scenePath) {
    auto scene = loadScene(scenePath);
    RenderOptions options;
    options.threads = static_cast<int>(state.range(0));
    options.quiet = true;
    RenderStats total;
    for (auto _ : state) {
        RenderStats stats;
        Film film = renderScene(*scene, options, stats);
        benchmark::DoNotOptimize(film.rgb.data());
        total.rays += stats.rays;
        total.cameraRays += stats.cameraRays;
    }
    state.counters["rays/s"] = benchmark::Counter(double(total.rays), benchmark::Counter::kIsRate);
    state.counters["camera_rays/s"] =
        benchmark::Counter(double(total.cameraRays), benchmark::Counter::kIsRate);
}

void BM_RenderDefaultScene(benchmark::State& state) {
    renderBenchmark(state, kSource + "/scenes/glulam-beam.json");
}

void BM_RenderWoodBox512(benchmark::State& state) {
    renderBenchmark(state, kSource + "/bench/scenes/wood-box-512.json");
}

// The same box with its preset's anatomy off: what fibres, rays and resin canals cost.
void BM_RenderWoodBox512AnatomyOff(benchmark::State& state) {
    renderBenchmark(state, kSource + "/bench/scenes/wood-box-512-anatomy-off.json");
}

BENCHMARK(BM_RenderDefaultScene)
    ->Arg(1)
    ->Arg(2)
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kSecond);
BENCHMARK(BM_RenderWoodBox512)
    ->Arg(1)
    ->Arg(2)
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kSecond);
BENCHMARK(BM_RenderWoodBox512AnatomyOff)
    ->Arg(1)
    ->Arg(2)
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace nenrin
