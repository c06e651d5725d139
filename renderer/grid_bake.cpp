#include "renderer/grid_bake.h"

#include <algorithm>

#include "renderer/parallel_tiles.h"
#include "util/progress.h"

namespace nenrin {

namespace {
// 8 x 8 x (1 or 8) samples per tile: small enough for tight candidate lists, large enough to
// amortise the index queries.
constexpr int kTile = 8;
}  // namespace

void bakeGrid(const WoodShader& shader, BakedGrid& grid, const BakeOptions& options) {
    grid.data.assign(grid.sampleCount() * BakedGrid::kChannels, 0.f);
    const int tz = grid.depth > 1 ? kTile : 1;
    const int nx = (grid.width + kTile - 1) / kTile;
    const int ny = (grid.height + kTile - 1) / kTile;
    const int nz = (grid.depth + tz - 1) / tz;
    const size_t tiles = size_t(nx) * ny * nz;
    ProgressReporter progress(static_cast<long long>(tiles), options.title, options.quiet);

    parallelTiles(tiles, options.threads, [&](size_t tile) {
        thread_local GrowthScratch scratch;
        thread_local std::vector<GrowthSample> samples;
        thread_local std::vector<Vec3> points;
        thread_local std::vector<WoodSample> wood;
        const int ti = static_cast<int>(tile % nx);
        const int tj = static_cast<int>((tile / nx) % ny);
        const int tk = static_cast<int>(tile / (size_t(nx) * ny));
        const int i0 = ti * kTile, i1 = std::min(grid.width, i0 + kTile);
        const int j0 = tj * kTile, j1 = std::min(grid.height, j0 + kTile);
        const int k0 = tk * tz, k1 = std::min(grid.depth, k0 + tz);
        points.clear();
        for (int k = k0; k < k1; ++k)
            for (int j = j0; j < j1; ++j)
                for (int i = i0; i < i1; ++i)
                    points.push_back(grid.origin + grid.stepX * i + grid.stepY * j +
                                     grid.stepZ * k);
        wood.resize(points.size());
        shader.evaluate(points, wood, scratch, samples);
        size_t n = 0;
        for (int k = k0; k < k1; ++k)
            for (int j = j0; j < j1; ++j)
                for (int i = i0; i < i1; ++i, ++n) {
                    float* px = grid.at(i, j, k);
                    const WoodSample& w = wood[n];
                    px[0] = static_cast<float>(w.albedo.r);
                    px[1] = static_cast<float>(w.albedo.g);
                    px[2] = static_cast<float>(w.albedo.b);
                    px[3] = static_cast<float>(w.coverage);
                    px[4] = static_cast<float>(w.T);
                    px[5] = static_cast<float>(w.knot);
                }
        progress.advance();
    });
    progress.done();
}

}  // namespace nenrin
