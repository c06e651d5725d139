#pragma once
/// A measured displacement of the points the growth field is evaluated at: the rings of a
/// photographed sample departing from the skeleton's cylinders (`nenrin fit` writes it, the
/// grain file's `warp`). Trilinear on a lattice of displacement vectors; beyond the lattice
/// it fades linearly to zero over one cell, so the field stays continuous everywhere.
/// Units: metres.

#include <vector>

#include "util/vec3.h"

namespace nenrin {

struct WarpParams {
    Vec3 origin;  ///< node (0, 0, 0)
    Vec3 step;    ///< node (i, j, k) lies at origin + (i step.x, j step.y, k step.z)
    int nx = 0, ny = 0, nz = 0;
    std::vector<Vec3> displacement;  ///< one per node, x fastest, then y, then z; empty = off
    bool enabled() const { return !displacement.empty(); }
};

/// The displacement at p.
Vec3 pointWarp(const Vec3& p, const WarpParams& warp);

}  // namespace nenrin
