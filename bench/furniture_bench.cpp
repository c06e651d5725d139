// The whole oak chair through `nenrin furniture` (issue 33): 17 parts, each its own board, a
// texture set of <texels>^2 per wood part and the 640 x 480 preview, on <threads> threads.
// BM_FurnitureChair/<texels>/<threads>; counter: parts/s.

#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "renderer/jobs/furniture_job.h"

namespace nenrin {
namespace {

void BM_FurnitureChair(benchmark::State& state) {
    namespace fs = std::filesystem;
    const std::string source = NENRIN_SOURCE_DIR;
    const fs::path out = fs::temp_directory_path() / "nenrin-bench-furniture";
    FurnitureJob job;
    job.model = source + "/tests/data/furniture/oak-chair/oakChair.obj";
    job.grain = source + "/scenes/grain/species/european-oak.json";
    job.unit = "cm";
    job.textureSize = static_cast<int>(state.range(0));
    job.threads = static_cast<int>(state.range(1));
    job.quiet = true;
    size_t parts = 0;
    for (auto _ : state) {
        fs::remove_all(out);
        job.output = out.string();
        parts += runFurnitureJob(job).parts;
    }
    fs::remove_all(out);
    state.counters["parts/s"] = benchmark::Counter(double(parts), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_FurnitureChair)
    ->Args({1024, 2})
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

}  // namespace
}  // namespace nenrin
