#include "renderer/bake/grid_bake.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "renderer/parallel_tiles.h"
#include "util/memory_budget.h"
#include "util/progress.h"

namespace nenrin {

namespace {
// A tile is one evaluateBatch call: 32 x 32 samples (slices) or 8 x 8 x 8 (volumes), listed
// as runs of 64 compact samples (8 x 8 or 4 x 4 x 4 chunks), the field's pruning unit. One
// index query per tile, tight candidate lists per chunk.
constexpr int kTile2D = 32, kChunk2D = 8;
constexpr int kTile3D = 8, kChunk3D = 4;
}  // namespace

int bakeTileLayers(bool volume) { return volume ? kTile3D : kTile2D; }

double bakeMemoryBytes(const BakedGrid& grid) {
    // The samples and a writer's copy of them (EXR channels, VDB grids).
    return 2.0 * double(grid.sampleCount()) * BakedGrid::kChannels * sizeof(float);
}

void bakeGrid(const WoodShader& shader, BakedGrid& grid, const BakeOptions& options) {
    requireMemory(bakeMemoryBytes(grid),
                  grid.isVolume()
                      ? fmt::format("a {} x {} x {} volume", grid.width, grid.height, grid.depth)
                      : fmt::format("a {} x {} slice", grid.width, grid.height),
                  "bake");
    grid.data.assign(grid.sampleCount() * BakedGrid::kChannels, 0.f);
    const bool volume = grid.isVolume();
    if (grid.layerBegin % bakeTileLayers(volume) != 0)
        throw std::invalid_argument("bakeGrid: band does not start on a tile");
    const int kTile = volume ? kTile3D : kTile2D;
    const int chunk = volume ? kChunk3D : kChunk2D;
    const int tz = volume ? kTile3D : 1;
    const int cz = volume ? kChunk3D : 1;
    // Whole tiles of the held layers only: along y for a slice, along z for a volume.
    const int firstTile = grid.layerBegin / kTile;
    const int layerTiles = (grid.storedEnd() + kTile - 1) / kTile - firstTile;
    const int nx = (grid.width + kTile - 1) / kTile;
    const int ny = volume ? (grid.height + kTile - 1) / kTile : layerTiles;
    const int nz = volume ? layerTiles : 1;
    const size_t tiles = size_t(nx) * ny * nz;
    ProgressReporter progress(static_cast<long long>(tiles), options.title, options.quiet);

    // Every sample is the wood's full surface response filtered over its cell: a slice's
    // pixel (with the plane's normal, for the end-grain term), a volume's cell (isotropic, no
    // surface), so a coarse bake fades to the mean instead of aliasing.
    const SurfaceFootprint footprint =
        volume ? SurfaceFootprint{{},
                                  {},
                                  std::sqrt(std::max({lengthSquared(grid.stepX),
                                                      lengthSquared(grid.stepY),
                                                      lengthSquared(grid.stepZ)})),
                                  {}}
               : SurfaceFootprint{grid.stepX, grid.stepY, 0, grid.normal};
    parallelTiles(tiles, options.threads, [&](size_t tile) {
        thread_local WoodScratch scratch;
        thread_local std::vector<Vec3> points;
        thread_local std::vector<SurfaceFootprint> footprints;
        thread_local std::vector<WoodSurfaceSample> wood;
        thread_local std::vector<std::array<int, 3>> indices;
        const int ti = static_cast<int>(tile % nx);
        const int tj = static_cast<int>((tile / nx) % ny) + (volume ? 0 : firstTile);
        const int tk = static_cast<int>(tile / (size_t(nx) * ny)) + (volume ? firstTile : 0);
        const int i0 = ti * kTile, i1 = std::min(grid.width, i0 + kTile);
        const int j0 = tj * kTile,
                  j1 = std::min(volume ? grid.height : grid.storedEnd(), j0 + kTile);
        const int k0 = tk * tz, k1 = std::min(volume ? grid.storedEnd() : 1, k0 + tz);
        points.clear();
        indices.clear();
        for (int ck = k0; ck < k1; ck += cz)
            for (int cj = j0; cj < j1; cj += chunk)
                for (int ci = i0; ci < i1; ci += chunk)
                    for (int k = ck; k < std::min(k1, ck + cz); ++k)
                        for (int j = cj; j < std::min(j1, cj + chunk); ++j)
                            for (int i = ci; i < std::min(i1, ci + chunk); ++i) {
                                points.push_back(grid.origin + grid.stepX * i + grid.stepY * j +
                                                 grid.stepZ * k);
                                indices.push_back({i, j, k});
                            }
        wood.resize(points.size());
        footprints.assign(points.size(), footprint);
        shader.evaluateSurface(points, footprints, wood, scratch);
        for (size_t n = 0; n < points.size(); ++n) {
            const auto [i, j, k] = indices[n];
            float* px = grid.at(i, j, k);
            const WoodSurfaceSample& w = wood[n];
            // Outside the felled log the channels stay black: A says so.
            const Rgb albedo = w.coverage > 0 ? w.albedo : Rgb{};
            px[0] = static_cast<float>(albedo.r);
            px[1] = static_cast<float>(albedo.g);
            px[2] = static_cast<float>(albedo.b);
            px[3] = static_cast<float>(w.coverage);
            px[4] = static_cast<float>(w.T);
            px[5] = static_cast<float>(w.knot);
        }
        progress.advance();
    });
    progress.done();
}

}  // namespace nenrin
