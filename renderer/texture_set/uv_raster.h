#pragma once
/// Rasterising a mesh's UV layout into texels, and gutter dilation past UV seams: the pure
/// functions behind `nenrin bake uv`, which bakes wood onto a mesh's UV layout as texture maps.
///
/// Geometry: texel (i, j) of a W x H map covers u in [i/W, (i+1)/W], v in [1-(j+1)/H, 1-j/H]:
/// row 0 is the TOP of the image (v = 1), as image files store it, and OBJ's v = 0 is the bottom
/// row. A texel's sample point is its centre ((i + 0.5)/W, 1 - (j + 0.5)/H). The rasteriser
/// works in texel space (x = u W, y = (1 - v) H), where that centre is exactly (i + 0.5, j + 0.5).

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "renderer/geometry/obj_mesh.h"

namespace nenrin {

/// Which triangle each texel of a W x H map samples, and where on it. Texels are row-major
/// (index j * width + i), row 0 at the top (v = 1).
struct UvRaster {
    int width = 0, height = 0;
    std::vector<int32_t> triangle;  ///< per texel: covering triangle (mesh index), -1 if none
    /// Per texel: weights of the triangle's corners (mesh.triangles[t][0..2]) at the sample
    /// point; sum 1, all >= 0. {0, 0, 0} for uncovered texels.
    std::vector<std::array<double, 3>> barycentric;
    /// Texels whose centre lies in 2+ triangles (by the fill rule). Rule: the lowest triangle
    /// index wins the texel; each such texel counts once however many triangles claim it.
    size_t overlappingTexels = 0;
    /// Triangles with any uv outside [0,1]^2 (they still rasterise where they overlap the map).
    size_t trianglesOutsideUnitSquare = 0;
    size_t degenerateTriangles = 0;  ///< zero (or non-finite) uv area: skipped
    /// Texels whose centre is in no triangle but whose square overlaps one with positive area
    /// (chart edges, seams): assigned to the nearest such triangle, barycentrics clamped onto it.
    size_t edgeTexels = 0;

    std::vector<uint8_t> covered() const;  ///< per texel: 1 where triangle >= 0, else 0
};

/// Rasterises every triangle's uv triangle, sampling texel centres; either winding works.
///
/// Interior texels: a centre strictly inside a triangle belongs to it. A centre exactly on an
/// edge belongs to the triangle for which that edge is a top or left edge in image space (y
/// down; a top edge is horizontal with the triangle below it, a left edge has the triangle to
/// its right). Edge functions are evaluated in double precision with each edge's endpoints in
/// a canonical order, so the two triangles of a shared edge see exactly opposite values: a
/// closed uv chart has no holes and no double coverage. Barycentrics are the edge functions
/// divided by their sum, so they reproduce the centre's uv to rounding.
///
/// Edge texels: a texel whose centre is in no triangle but whose square shares a positive area
/// with one or more triangles (touching only along a texel border or at a corner does not count)
/// goes to the triangle nearest its centre (Euclidean distance in texel units; ties to the lower
/// index), with barycentrics of the closest point of that triangle, so the sample point lies on
/// the surface. These make the edges of charts fully covered before dilation.
///
/// Throws std::invalid_argument if the mesh has no uvs, a triangle indexes past the uvs, or
/// width/height < 1. Deterministic and single-threaded; the cost is the sum of the triangles'
/// texel bounding boxes.
UvRaster rasterizeUv(const TriangleMesh& mesh, int width, int height);

/// Gutter padding: grows the covered region outwards by `texels` rings of 8-neighbours, so
/// mip-mapping and bilinear lookups do not bleed background into the wood. Each new texel of a
/// ring takes the average of its neighbours covered before that ring (summed in a fixed
/// neighbour order, in double), so a ring never feeds itself and the result does not depend on
/// the visiting order. `pixels` holds `channels` values per texel, row-major; texels still
/// uncovered afterwards keep their values. `covered` (1 = covered) is updated.
///
/// Throws std::invalid_argument if channels < 1, width/height < 1, texels < 0, or the sizes of
/// `pixels` / `covered` do not match.
void dilate(std::vector<float>& pixels, int channels, int width, int height,
            std::vector<uint8_t>& covered, int texels);

}  // namespace nenrin
