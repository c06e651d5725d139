// Im, Shinagawa & Kunii's interacting-tree stand: simulation and felling speed.
#include <benchmark/benchmark.h>

#include "skeleton/sources/kunii/kunii_fell.h"
#include "skeleton/sources/kunii/kunii_stand.h"

namespace {

// BM_KuniiStand/trees/years on the default 40 m plot (germination adds trees as it goes).
void BM_KuniiStand(benchmark::State& state) {
    nenrin::StandOptions o;
    o.trees = static_cast<int>(state.range(0));
    o.years = static_cast<int>(state.range(1));
    size_t trees = 0;
    for (auto _ : state) {
        nenrin::Stand stand = nenrin::simulateStand(o);
        trees = stand.trees.size();
        benchmark::DoNotOptimize(trees);
    }
    state.counters["trees_ever"] = static_cast<double>(trees);
}
BENCHMARK(BM_KuniiStand)->Args({100, 100})->Args({100, 200})->Unit(benchmark::kMillisecond);

void BM_KuniiFell(benchmark::State& state) {
    nenrin::StandOptions o;
    nenrin::Stand stand = nenrin::simulateStand(o);
    uint32_t id = nenrin::pickStandTree(stand, nenrin::TreePick::Dominant);
    for (auto _ : state)
        benchmark::DoNotOptimize(nenrin::fellStandTree(stand, id).segments().size());
}
BENCHMARK(BM_KuniiFell)->Unit(benchmark::kMillisecond);

}  // namespace
