#pragma once
/// What a fuzz target does with a skeleton or grain that was read without an error: grows the
/// field and shades points in and around the tree, as a render or bake would, and fails if any
/// result is not finite. A file the readers accept must never put a NaN or Inf into a picture.

#include "grain/grain_params.h"
#include "skeleton/skeleton.h"

namespace nenrin::fuzz {

/// Shades a grid over the skeleton's bounding box (and a margin), its nodes and far points.
void probeWood(const Skeleton& skeleton, const GrainParams& params);

/// A small tree with a trunk and two branches, for targets that read grain parameters.
Skeleton probeTree();

}  // namespace nenrin::fuzz
