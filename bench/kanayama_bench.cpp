// Kanayama growth model: the light environment's scaling (Embree occlusion rays vs the paper's
// O(n^2) projection of every sphere onto the dome) and whole simulations.
#include <benchmark/benchmark.h>

#include "skeleton/sources/kanayama/kanayama_growth.h"
#include "skeleton/sources/kanayama/kanayama_light.h"
#include "util/hash.h"

namespace {

// n leaf spheres in a crown whose volume grows with n, so the density (and the number of
// spheres a ray meets) stays that of a real crown: ~0.1 m spheres, ~40 per m^3.
std::vector<nenrin::LeafSphere> crown(int n) {
    double side = std::cbrt(n / 40.0);
    std::vector<nenrin::LeafSphere> spheres;
    for (int i = 0; i < n; ++i) {
        nenrin::Vec3 c{(nenrin::uniform01(9, i, 0) - 0.5) * side,
                       (nenrin::uniform01(9, i, 1) - 0.5) * side,
                       1 + nenrin::uniform01(9, i, 2) * side};
        spheres.push_back({c, 0.05 + 0.1 * nenrin::uniform01(9, i, 3)});
    }
    return spheres;
}

void BM_KanayamaLightEmbree(benchmark::State& state) {
    auto spheres = crown(static_cast<int>(state.range(0)));
    nenrin::SkyDome dome = nenrin::makeSkyDome(96);
    nenrin::LeafLightParameters p;
    nenrin::LeafLightTracer tracer;
    for (auto _ : state) benchmark::DoNotOptimize(tracer.compute(spheres, dome, p).data());
    state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_KanayamaLightEmbree)
    ->Name("BM_KanayamaLight/Embree")
    ->RangeMultiplier(10)
    ->Range(100, 10000)
    ->Arg(3000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_KanayamaLightReference(benchmark::State& state) {
    auto spheres = crown(static_cast<int>(state.range(0)));
    nenrin::SkyDome dome = nenrin::makeSkyDome(96);
    nenrin::LeafLightParameters p;
    for (auto _ : state)
        benchmark::DoNotOptimize(nenrin::leafLightReference(spheres, dome, p).data());
    state.SetItemsProcessed(state.iterations() * state.range(0));
}
void BM_KanayamaLightEmbreePackets(benchmark::State& state) {
    auto spheres = crown(static_cast<int>(state.range(0)));
    nenrin::SkyDome dome = nenrin::makeSkyDome(96);
    nenrin::LeafLightParameters p;
    p.packets = true;
    nenrin::LeafLightTracer tracer;
    for (auto _ : state) benchmark::DoNotOptimize(tracer.compute(spheres, dome, p).data());
    state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_KanayamaLightEmbreePackets)
    ->Name("BM_KanayamaLight/EmbreePackets16")
    ->RangeMultiplier(10)
    ->Range(100, 10000)
    ->Arg(3000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK(BM_KanayamaLightReference)
    ->Name("BM_KanayamaLight/Reference")
    ->RangeMultiplier(10)
    ->Range(100, 10000)
    ->Arg(3000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(0.2);

void growPreset(benchmark::State& state, const char* name) {
    nenrin::KanayamaOptions o = nenrin::kanayamaPreset(name);
    size_t shoots = 0;
    for (auto _ : state) shoots = nenrin::growKanayamaTree(o).shoots.size();
    state.counters["shoots"] = static_cast<double>(shoots);
}
void BM_KanayamaCherry15(benchmark::State& state) { growPreset(state, "cherry"); }
void BM_KanayamaZelkova15(benchmark::State& state) { growPreset(state, "zelkova"); }
void BM_KanayamaAzalea15(benchmark::State& state) { growPreset(state, "azalea"); }
BENCHMARK(BM_KanayamaCherry15)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_KanayamaZelkova15)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_KanayamaAzalea15)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
