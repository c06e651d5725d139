#pragma once
/// Two tools for finding the pieces of a mesh: vertex ids that treat equal positions as one
/// (the loaders split vertices at uv and normal seams), and a union-find over triangles.

#include <cstdint>
#include <vector>

#include "renderer/geometry/obj_mesh.h"

namespace nenrin {

/// Per vertex, an id shared by every vertex at exactly the same position (+0 and -0 equal).
std::vector<uint32_t> weldedVertexIds(const TriangleMesh& mesh);

/// Disjoint sets of indices 0..n-1; each set is led by its lowest index.
class DisjointSets {
public:
    explicit DisjointSets(size_t n);
    size_t find(size_t i);
    void join(size_t a, size_t b);

private:
    std::vector<size_t> parent_;
};

}  // namespace nenrin
