#include "renderer/furniture/model_parts.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <numeric>
#include <unordered_map>

#include "renderer/geometry/gltf_mesh.h"
#include "util/input_error.h"

namespace nenrin {

namespace {

/// Union-find over triangles.
class Pieces {
public:
    explicit Pieces(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
    size_t find(size_t i) {
        while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
        return i;
    }
    void join(size_t a, size_t b) {
        a = find(a), b = find(b);
        if (a != b) parent_[std::max(a, b)] = std::min(a, b);  // the first triangle leads
    }

private:
    std::vector<size_t> parent_;
};

struct PositionKey {
    uint64_t x, y, z;
    bool operator==(const PositionKey&) const = default;
};
struct PositionHash {
    size_t operator()(const PositionKey& k) const {
        return std::hash<uint64_t>()(k.x * 0x9E3779B97F4A7C15ull ^ k.y * 0xC2B2AE3D27D4EB4Full ^
                                     k.z);
    }
};

/// Welded vertex ids: vertices at exactly the same position (split at uv or normal seams by
/// the loaders) are one.
std::vector<uint32_t> weld(const TriangleMesh& m) {
    std::unordered_map<PositionKey, uint32_t, PositionHash> ids;
    std::vector<uint32_t> welded(m.positions.size());
    for (size_t i = 0; i < m.positions.size(); ++i) {
        const Vec3& p = m.positions[i];
        // +0.0 and -0.0 are one position.
        PositionKey key{std::bit_cast<uint64_t>(p.x + 0.0), std::bit_cast<uint64_t>(p.y + 0.0),
                        std::bit_cast<uint64_t>(p.z + 0.0)};
        welded[i] = ids.try_emplace(key, static_cast<uint32_t>(ids.size())).first->second;
    }
    return welded;
}

double triangleArea(const TriangleMesh& m, const std::array<uint32_t, 3>& t) {
    return 0.5 * length(cross(m.positions[t[1]] - m.positions[t[0]],
                              m.positions[t[2]] - m.positions[t[0]]));
}

/// The piece made of `triangles` of `model`, with its own compact vertex arrays.
ModelPart extract(const TriangleMesh& model, const std::vector<size_t>& triangles) {
    ModelPart part;
    std::unordered_map<uint32_t, uint32_t> local;
    std::map<uint32_t, double> materialArea;
    for (size_t t : triangles) {
        std::array<uint32_t, 3> tri;
        for (int c = 0; c < 3; ++c) {
            const uint32_t v = model.triangles[t][c];
            auto [it, isNew] =
                local.try_emplace(v, static_cast<uint32_t>(part.mesh.positions.size()));
            if (isNew) {
                part.mesh.positions.push_back(model.positions[v]);
                if (!model.normals.empty()) part.mesh.normals.push_back(model.normals[v]);
                if (!model.uvs.empty()) part.mesh.uvs.push_back(model.uvs[v]);
            }
            tri[c] = it->second;
        }
        part.mesh.triangles.push_back(tri);
        const double a = triangleArea(model, model.triangles[t]);
        part.area += a;
        if (!model.triangleMaterials.empty()) materialArea[model.triangleMaterials[t]] += a;
    }
    if (!materialArea.empty()) {
        auto most = std::max_element(materialArea.begin(), materialArea.end(),
                                     [](auto& a, auto& b) { return a.second < b.second; });
        part.material = model.materialNames[most->first];
    }
    return part;
}

}  // namespace

std::vector<ModelPart> splitModelParts(const TriangleMesh& model, const std::string& file) {
    const size_t n = model.triangles.size();
    const std::vector<uint32_t> welded = weld(model);
    auto groupOf = [&](size_t t) {
        return model.triangleGroups.empty() ? 0u : model.triangleGroups[t];
    };
    // Triangles of one group sharing a welded vertex are one piece.
    Pieces pieces(n);
    std::unordered_map<uint64_t, size_t> firstAt;  // (group, welded vertex) -> a triangle
    for (size_t t = 0; t < n; ++t)
        for (uint32_t v : model.triangles[t]) {
            const uint64_t key = (uint64_t(groupOf(t)) << 32) | welded[v];
            auto [it, isNew] = firstAt.try_emplace(key, t);
            if (!isNew) pieces.join(it->second, t);
        }
    std::map<size_t, std::vector<size_t>> byRoot;  // ordered by the piece's first triangle
    for (size_t t = 0; t < n; ++t) byRoot[pieces.find(t)].push_back(t);
    if (byRoot.size() > kMaxModelParts)
        throw InputError(file, "",
                         fmt::format("{} separate pieces: expected at most {} parts (is this a "
                                     "scan or a point cloud rather than a furniture model?)",
                                     byRoot.size(), kMaxModelParts));
    std::map<uint32_t, int> piecesInGroup, numbered;
    for (const auto& [root, tris] : byRoot) ++piecesInGroup[groupOf(root)];
    std::vector<ModelPart> parts;
    for (const auto& [root, tris] : byRoot) {
        ModelPart part = extract(model, tris);
        const uint32_t g = groupOf(root);
        std::string name =
            model.groupNames.empty() || model.groupNames[g].empty() ? "part" : model.groupNames[g];
        if (piecesInGroup[g] > 1) name += fmt::format(".{}", ++numbered[g]);
        part.name = name;
        parts.push_back(std::move(part));
    }
    return parts;
}

TriangleMesh loadFurnitureModel(const std::string& path, double metresPerUnit) {
    TriangleMesh mesh = isGltfPath(path) ? loadGltfMesh(path) : loadObjMesh(path);
    for (Vec3& p : mesh.positions) p = p * metresPerUnit;
    return mesh;
}

}  // namespace nenrin
