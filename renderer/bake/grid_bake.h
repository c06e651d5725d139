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

/// Fills grid.data (resizing it). Bitwise identical for any thread count.
void bakeGrid(const WoodShader& shader, BakedGrid& grid, const BakeOptions& options);

}  // namespace nenrin
