#pragma once
/// Evaluates the wood at every sample of a BakedGrid (its origin and steps already set), in
/// coherent tiles on a thread pool, with progress on stderr.

#include <string>

#include "renderer/bake/baked_grid.h"
#include "shader/wood_shader.h"

namespace nenrin {

struct BakeOptions {
    int threads = 0;  ///< 0 = all cores
    bool quiet = false;
    std::string title = "Baking";
};

/// Layers per bake tile (rows of a slice, z slices of a volume): the bands of a split bake
/// start on multiples of it, so every sample is computed in the same batch as in a whole bake.
int bakeTileLayers(bool volume);

/// Memory a bake of this grid takes (its samples and a writer's copy), bytes.
double bakeMemoryBytes(const BakedGrid& grid);

/// Fills grid.data (resizing it) for the layers the grid holds (grid.layerBegin must be a
/// multiple of bakeTileLayers). Bitwise identical for any thread count and split. A grid over
/// the memory limit (util/memory_budget.h) is refused with an InputError before allocating.
void bakeGrid(const WoodShader& shader, BakedGrid& grid, const BakeOptions& options);

}  // namespace nenrin
