#pragma once
/// A "cookie": a disc sawn across the log at some height, its outline following the bark of
/// the felled tree (where T reaches the felling time, found per azimuth) plus a bark rim, with
/// radial drying checks cut into it.
/// Object space: the pith at the origin, the disc's faces at y = +-thickness/2 (y up = along
/// the trunk), so treeFromObject puts object y along tree z at the cut height.

#include "grain/growth_field.h"
#include "renderer/geometry/obj_mesh.h"
#include "renderer/geometry/rigid_transform.h"

namespace nenrin {

struct LogSliceParams {
    double height = 1.0;      ///< m: along the trunk, of the disc's centre
    double thickness = 0.04;  ///< m
    double bark = 0.008;      ///< m: bark added outside the wood
    int segments = 256;       ///< around the outline
    double maxRadius = 0.3;   ///< m: outline radius when the grain has no felling time
    /// Radial drying checks: V-shaped cracks opening at the bark (a cookie shrinks more
    /// around its circumference than along its radius as it dries).
    int checks = 3;
    double checkDepth = 0.35;   ///< share of the radius they run in from the bark
    double checkWidth = 0.004;  ///< m: opening at the bark
    uint64_t checkSeed = 1;
};

TriangleMesh logSliceMesh(const GrowthField& field, const LogSliceParams& params);
/// Tree space from the slice's object space.
RigidTransform logSliceTreeFromObject(const GrowthField& field, const LogSliceParams& params);

}  // namespace nenrin
