// UV bake benchmark (issue 7): a full set of 2048 x 2048 maps for a 10k-triangle mesh (a board
// 0.6 x 0.15 m as a 100 x 50 quad grid with a uv grid over [0.02, 0.98]^2), 1 and 2 threads.
// Goal: under 10 s on a 2-core machine. Counter: texels/s.

#include <benchmark/benchmark.h>

#include <string>

#include "renderer/scene_file.h"
#include "renderer/texture_set/uv_bake.h"

namespace nenrin {
namespace {

std::shared_ptr<TriangleMesh> gridBoard(int nx, int ny) {
    auto m = std::make_shared<TriangleMesh>();
    for (int y = 0; y <= ny; ++y)
        for (int x = 0; x <= nx; ++x) {
            double u = double(x) / nx, v = double(y) / ny;
            m->positions.push_back({0.6 * (u - 0.5), 0, -0.15 * (v - 0.5)});
            m->normals.push_back({0, 1, 0});
            m->uvs.push_back({0.02 + 0.96 * u, 0.02 + 0.96 * v});
        }
    for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x) {
            uint32_t a = y * (nx + 1) + x, b = a + 1, c = a + nx + 1, d = c + 1;
            m->triangles.push_back({a, b, d});
            m->triangles.push_back({a, d, c});
        }
    return m;
}

void BM_UvBake(benchmark::State& state) {
    auto scene = loadScene(std::string(NENRIN_SOURCE_DIR) + "/bench/scenes/uv-bake.json");
    scene->objects[0].mesh = gridBoard(100, 50);  // 10 000 triangles
    UvBakeOptions options;
    options.width = options.height = static_cast<int>(state.range(0));
    options.threads = static_cast<int>(state.range(1));
    options.quiet = true;
    for (auto _ : state) {
        UvMaps maps = bakeUvMaps(*scene, scene->objects[0], options);
        benchmark::DoNotOptimize(maps.baseColour.data());
    }
    state.counters["texels/s"] = benchmark::Counter(
        double(options.width) * options.height * state.iterations(), benchmark::Counter::kIsRate);
}

BENCHMARK(BM_UvBake)->Args({2048, 1})->Args({2048, 2})->Iterations(1)->UseRealTime()->Unit(
    benchmark::kSecond);

}  // namespace
}  // namespace nenrin
