#pragma once
/// UV charts for a part whose own UVs cannot be baked on (none, degenerate or overlapping, as
/// the oak chair's, where every corner of a face shares one uv): each triangle is projected
/// along the axis of the part's frame its normal is nearest (a box projection), connected
/// triangles of one projection form a chart, and the charts are packed into the unit square
/// on shelves, tallest first, with a gutter between them. One scale for every chart, so a
/// texel covers the same wood everywhere. Wherever a projection contains the fibre, u runs
/// along it (the baked anisotropy then points along u), and every chart keeps the surface's
/// orientation (u x v along the outward normal), so normal maps bake the right way round.

#include "renderer/furniture/part_frame.h"
#include "renderer/geometry/obj_mesh.h"

namespace nenrin {

struct PartCharts {
    TriangleMesh mesh;  ///< the part with its new uvs (vertices split where charts meet)
    int charts = 0;
    double metresPerUv = 0;  ///< the scale: 1 in uv is this much surface
};

/// `gutter`: space between charts and around the square's edge, in uv units (texels / the
/// texture's size). Keeps the part's normals if it has them.
PartCharts chartPart(const TriangleMesh& part, const PartFrame& frame, double gutter);

}  // namespace nenrin
