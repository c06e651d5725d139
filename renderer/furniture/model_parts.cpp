#include "renderer/furniture/model_parts.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

#include "renderer/furniture/welded_vertices.h"
#include "renderer/geometry/gltf_mesh.h"
#include "util/input_error.h"

namespace nenrin {

double triangleArea(const TriangleMesh& m, const std::array<uint32_t, 3>& t) {
    return 0.5 * length(cross(m.positions[t[1]] - m.positions[t[0]],
                              m.positions[t[2]] - m.positions[t[0]]));
}

double surfaceArea(const TriangleMesh& m) {
    double area = 0;
    for (const auto& t : m.triangles) area += triangleArea(m, t);
    return area;
}

namespace {

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
    const std::vector<uint32_t> welded = weldedVertexIds(model);
    auto groupOf = [&](size_t t) {
        return model.triangleGroups.empty() ? 0u : model.triangleGroups[t];
    };
    // Triangles of one group sharing a welded vertex are one piece.
    DisjointSets pieces(n);
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
