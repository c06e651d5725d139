// Hayashi & Takahashi conifer generation speed: a 20-year sugi with all four orders (foliage
// included) must stay under a second; the counters give the tree's size.
#include <benchmark/benchmark.h>

#include "skeleton/sources/hayashi/hayashi_conifer.h"

namespace {

void growAndCount(benchmark::State& state, const std::string& preset, int years, int maxOrder) {
    nenrin::HayashiOptions o = nenrin::hayashiPreset(preset);
    o.years = years;
    o.maxOrder = maxOrder;
    size_t segments = 0, chains = 0;
    for (auto _ : state) {
        nenrin::HayashiTree tree = nenrin::growHayashiConifer(o);
        segments = tree.skeleton.segments().size();
        chains = tree.skeleton.chains().size();
        benchmark::DoNotOptimize(segments);
    }
    state.counters["segments"] = static_cast<double>(segments);
    state.counters["chains"] = static_cast<double>(chains);
}

void BM_HayashiSugi20(benchmark::State& state) {
    growAndCount(state, "sugi", 20, static_cast<int>(state.range(0)));
}
BENCHMARK(BM_HayashiSugi20)->DenseRange(1, 4)->Unit(benchmark::kMillisecond);

void BM_HayashiPine20(benchmark::State& state) { growAndCount(state, "pine", 20, 4); }
BENCHMARK(BM_HayashiPine20)->Unit(benchmark::kMillisecond);

void BM_HayashiHinoki20(benchmark::State& state) { growAndCount(state, "hinoki", 20, 4); }
BENCHMARK(BM_HayashiHinoki20)->Unit(benchmark::kMillisecond);

}  // namespace
