// Akagi & Kitajima: MCMC fit of one species with the default chain (10000 burn-in + 1000
// samples, the paper's), one posterior-predictive draw, and generating one tree.
#include <benchmark/benchmark.h>

#include "skeleton/sources/akagi/akagi_model.h"

namespace {

void BM_AkagiFit(benchmark::State& state, const std::string& species) {
    nenrin::ObservationTable table = nenrin::akagiSpeciesTable(species);
    for (auto _ : state) benchmark::DoNotOptimize(nenrin::fitAkagiModel(table).params[0].rateMean);
}
BENCHMARK_CAPTURE(BM_AkagiFit, akagashi, std::string("akagashi"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AkagiFit, akaezomatsu, std::string("akaezomatsu"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AkagiFit, aomoji, std::string("aomoji"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AkagiFit, keyaki, std::string("keyaki"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AkagiFit, yabunikkei, std::string("yabunikkei"))
    ->Unit(benchmark::kMillisecond);

void BM_AkagiDraw(benchmark::State& state) {
    nenrin::AkagiFit fit = nenrin::fitAkagiModel(nenrin::akagiSpeciesTable("keyaki"));
    nenrin::SplitMix rng(1);
    for (auto _ : state) benchmark::DoNotOptimize(nenrin::drawAkagiParams(fit, rng).height);
}
BENCHMARK(BM_AkagiDraw)->Unit(benchmark::kMicrosecond);

// One tree from the keyaki table's mean parameters, skeleton included.
void BM_AkagiGenerate(benchmark::State& state) {
    nenrin::AkagiFit fit = nenrin::fitAkagiModel(nenrin::akagiSpeciesTable("keyaki"));
    uint64_t seed = 0;
    for (auto _ : state)
        benchmark::DoNotOptimize(
            nenrin::generateAkagiTree(fit.initialGuess, seed++, 40).skeleton.nodes().size());
}
BENCHMARK(BM_AkagiGenerate)->Unit(benchmark::kMicrosecond);

}  // namespace
