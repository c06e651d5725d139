#pragma once
/// The integrator: unidirectional path tracing with next-event estimation and multiple
/// importance sampling (power heuristic), Russian roulette from the third vertex on (depth 2), and
/// a maximum depth.
///
/// Work is split into tiles of 16 x 16 pixels run in parallel (TBB). Inside a tile all samples
/// of all pixels travel together, one bounce at a time, so that camera rays go to Embree in
/// packets of 16 and the wood is evaluated in coherent batches (per lamella), which the growth
/// field needs to be fast. Every random number is a pure function of (seed, pixel, sample,
/// dimension): the image is bitwise the same for any number of threads.
///
/// Wood at the camera hit gets the full surface response (filtered rings, fibre highlight,
/// relief bump); at later bounces, where the light is already blurred, only its albedo.
///
/// path_tracer.cpp keeps the loop; the parts live beside what they are about (listed in
/// renderer/README.md): the material step in material_bsdf.h, next-event estimation in
/// direct_light.h, the wood in wood_hits.h, adaptive sampling in adaptive_sampling.h, the
/// film's tile sums in film_tile.h, the random dimensions in sample_dimensions.h.

#include <cstdint>

#include "renderer/film.h"
#include "renderer/row_band.h"
#include "renderer/scene.h"

namespace nenrin {

/// Pixels per side of the tiles the frame is rendered in (and adaptive sampling decides in):
/// the bands of a split render start on multiples of it.
inline constexpr int kRenderTileSize = 16;

struct RenderOptions {
    int threads = 0;  ///< 0 = all cores
    bool quiet = false;
    /// Only these rows (a split job's part); begin must be a multiple of kRenderTileSize.
    RowBand rows;
};

struct RenderStats {
    double seconds = 0;
    uint64_t cameraRays = 0;
    uint64_t rays = 0;  ///< all rays traced: camera, bounce and shadow rays
};

/// Renders with scene.settings (resolution, spp, depth, seed); the film holds options.rows.
Film renderScene(const Scene& scene, const RenderOptions& options, RenderStats& stats);

}  // namespace nenrin
