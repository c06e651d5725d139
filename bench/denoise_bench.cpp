// Denoiser benchmark (issue 34, part 1): `denoiseFilm` on table-top-room rendered once at
// 320 x 200 and 32 spp (scripts/bench-noise's size and the spp its goal is reached near), on 1
// and 2 threads. The time counts toward the denoised render's time to a clean image.

#include <benchmark/benchmark.h>

#include <string>

#include "renderer/denoise/atrous_denoiser.h"
#include "renderer/path_tracer.h"
#include "renderer/scene_file.h"

namespace nenrin {
namespace {

const Film& tableTopRoom32Spp() {
    static const Film film = [] {
        auto scene = loadScene(std::string(NENRIN_SOURCE_DIR) + "/scenes/table-top-room.json");
        scene->settings.width = 320;
        scene->settings.height = 200;
        scene->settings.spp = 32;
        RenderOptions options;
        options.quiet = true;
        RenderStats stats;
        return renderScene(*scene, options, stats);
    }();
    return film;
}

void BM_Denoise(benchmark::State& state) {
    const Film& noisy = tableTopRoom32Spp();
    DenoiseOptions options;
    options.threads = static_cast<int>(state.range(0));
    options.samples = 32;
    for (auto _ : state) {
        state.PauseTiming();
        Film film = noisy;
        state.ResumeTiming();
        denoiseFilm(film, options);
        benchmark::DoNotOptimize(film.rgb.data());
    }
}

BENCHMARK(BM_Denoise)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace nenrin
