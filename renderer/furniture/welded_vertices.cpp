#include "renderer/furniture/welded_vertices.h"

#include <algorithm>
#include <array>
#include <bit>
#include <map>
#include <numeric>

namespace nenrin {

std::vector<uint32_t> weldedVertexIds(const TriangleMesh& m) {
    std::map<std::array<uint64_t, 3>, uint32_t> ids;
    std::vector<uint32_t> out(m.positions.size());
    for (size_t i = 0; i < m.positions.size(); ++i) {
        const Vec3& p = m.positions[i];
        const std::array<uint64_t, 3> key{std::bit_cast<uint64_t>(p.x + 0.0),
                                          std::bit_cast<uint64_t>(p.y + 0.0),
                                          std::bit_cast<uint64_t>(p.z + 0.0)};
        out[i] = ids.try_emplace(key, static_cast<uint32_t>(ids.size())).first->second;
    }
    return out;
}

DisjointSets::DisjointSets(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }

size_t DisjointSets::find(size_t i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
}

void DisjointSets::join(size_t a, size_t b) {
    a = find(a), b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
}

}  // namespace nenrin
