#include "renderer/furniture/crease_normals.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <tuple>

#include "renderer/furniture/welded_vertices.h"

namespace nenrin {

namespace {

/// The angle of triangle `t` at its corner on welded position `w`: weighting by it makes a
/// vertex's normal independent of how the faces round it are cut into triangles.
double cornerAngle(const TriangleMesh& mesh, uint32_t t, const std::vector<uint32_t>& welded,
                   uint32_t w) {
    const auto& tri = mesh.triangles[t];
    for (int c = 0; c < 3; ++c)
        if (welded[tri[c]] == w) {
            const Vec3 a = mesh.positions[tri[(c + 1) % 3]] - mesh.positions[tri[c]];
            const Vec3 b = mesh.positions[tri[(c + 2) % 3]] - mesh.positions[tri[c]];
            if (lengthSquared(a) == 0 || lengthSquared(b) == 0) return 0;
            return std::acos(std::clamp(dot(normalize(a), normalize(b)), -1.0, 1.0));
        }
    return 0;
}

}  // namespace

TriangleMesh withCreaseNormals(const TriangleMesh& mesh, double creaseDegrees) {
    const size_t n = mesh.triangles.size();
    const std::vector<uint32_t> welded = weldedVertexIds(mesh);
    // Each triangle's unit normal (zero without area) and the triangles round each welded
    // position (the ids are dense: 0 .. positions - 1 at most).
    std::vector<Vec3> faceNormal(n);
    std::vector<std::vector<uint32_t>> around(mesh.positions.size());
    for (size_t t = 0; t < n; ++t) {
        const auto& tri = mesh.triangles[t];
        const Vec3 normal = cross(mesh.positions[tri[1]] - mesh.positions[tri[0]],
                                  mesh.positions[tri[2]] - mesh.positions[tri[0]]);
        faceNormal[t] = lengthSquared(normal) > 0 ? normalize(normal) : Vec3{};
        for (uint32_t v : tri) around[welded[v]].push_back(uint32_t(t));
    }
    const double cosCrease = std::cos(creaseDegrees * std::numbers::pi / 180);

    TriangleMesh out;
    out.triangles.resize(n);
    out.triangleGroups = mesh.triangleGroups;
    out.triangleMaterials = mesh.triangleMaterials;
    out.groupNames = mesh.groupNames;
    out.materialNames = mesh.materialNames;
    // A vertex of the output: the input vertex and the normal's bits.
    std::map<std::tuple<uint32_t, double, double, double>, uint32_t> vertexOf;
    for (size_t t = 0; t < n; ++t) {
        const Vec3& own = faceNormal[t];
        for (int c = 0; c < 3; ++c) {
            const uint32_t v = mesh.triangles[t][c];
            Vec3 sum;
            for (uint32_t o : around[welded[v]]) {
                const Vec3& other = faceNormal[o];
                // A degenerate triangle joins every neighbour; a real one those within the
                // crease angle.
                if (lengthSquared(own) == 0 || dot(own, other) >= cosCrease)
                    sum = sum + other * cornerAngle(mesh, o, welded, welded[v]);
            }
            Vec3 normal = lengthSquared(sum) > 0 ? normalize(sum) : Vec3{};
            if (lengthSquared(normal) == 0) normal = lengthSquared(own) > 0 ? own : Vec3{0, 0, 1};
            auto [it, isNew] = vertexOf.try_emplace({v, normal.x, normal.y, normal.z},
                                                    uint32_t(out.positions.size()));
            if (isNew) {
                out.positions.push_back(mesh.positions[v]);
                out.normals.push_back(normal);
                if (!mesh.uvs.empty()) out.uvs.push_back(mesh.uvs[v]);
            }
            out.triangles[t][c] = it->second;
        }
    }
    return out;
}

}  // namespace nenrin
