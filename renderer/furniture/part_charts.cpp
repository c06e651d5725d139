#include "renderer/furniture/part_charts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <unordered_map>

#include "renderer/furniture/welded_vertices.h"

namespace nenrin {

namespace {

/// The projection of each of the six faces of the part's box: the outward axis, and the two
/// in-plane axes (u, v) with u x v along it. Axes: 0 fibre, 1 width, 2 thickness.
struct Projection {
    int u, v;
    double su, sv;  ///< signs
};
// +fibre, -fibre, +width, -width, +thickness, -thickness
constexpr Projection kProjections[6] = {{1, 2, 1, 1}, {1, 2, 1, -1}, {0, 2, 1, -1},
                                        {0, 2, 1, 1}, {0, 1, 1, 1},  {0, 1, 1, -1}};

int projectionOf(const Vec3& n, const PartFrame& f) {
    int best = 0;
    double bestDot = -1;
    for (int k = 0; k < 3; ++k) {
        const double d = dot(n, f.axes[k]);
        if (std::abs(d) > bestDot) bestDot = std::abs(d), best = 2 * k + (d < 0 ? 1 : 0);
    }
    return best;
}

struct Chart {
    std::vector<size_t> triangles;
    int projection = 0;
    double u0 = INFINITY, v0 = INFINITY, u1 = -INFINITY, v1 = -INFINITY;  ///< metres
    double x = 0, y = 0;  ///< packed place of (u0, v0), in metres of the square
};

/// Shelf packing into a square of side `side` (m) with `gap` (m) between charts and at the
/// edges. False when they do not fit.
bool pack(std::vector<Chart*>& charts, double side, double gap) {
    double x = gap, y = gap, shelf = 0;
    for (Chart* c : charts) {
        const double w = c->u1 - c->u0, h = c->v1 - c->v0;
        if (x + w + gap > side) x = gap, y += shelf + gap, shelf = 0;
        if (x + w + gap > side || y + h + gap > side) return false;
        c->x = x, c->y = y;
        x += w + gap;
        shelf = std::max(shelf, h);
    }
    return true;
}

}  // namespace

PartCharts chartPart(const TriangleMesh& part, const PartFrame& frame, double gutter) {
    const size_t n = part.triangles.size();
    std::vector<int> label(n);
    for (size_t t = 0; t < n; ++t) {
        const auto& tri = part.triangles[t];
        const Vec3 e = cross(part.positions[tri[1]] - part.positions[tri[0]],
                             part.positions[tri[2]] - part.positions[tri[0]]);
        label[t] = projectionOf(lengthSquared(e) > 0 ? normalize(e) : frame.axes[2], frame);
    }
    // Charts: triangles of one projection sharing an edge.
    const std::vector<uint32_t> welded = weldedVertexIds(part);
    DisjointSets charts(n);
    std::unordered_map<uint64_t, size_t> edgeOwner;
    for (size_t t = 0; t < n; ++t)
        for (int c = 0; c < 3; ++c) {
            uint32_t a = welded[part.triangles[t][c]], b = welded[part.triangles[t][(c + 1) % 3]];
            if (a > b) std::swap(a, b);
            const uint64_t key = (uint64_t(a) << 32 | b) * 8 + uint64_t(label[t]);
            auto [it, isNew] = edgeOwner.try_emplace(key, t);
            if (!isNew) charts.join(it->second, t);
        }
    std::map<size_t, Chart> byRoot;
    auto project = [&](const Vec3& p, int k) {
        const Projection& pr = kProjections[k];
        const Vec3 d = p - frame.centre;
        return std::array<double, 2>{pr.su * dot(d, frame.axes[pr.u]),
                                     pr.sv * dot(d, frame.axes[pr.v])};
    };
    for (size_t t = 0; t < n; ++t) {
        Chart& c = byRoot[charts.find(t)];
        c.projection = label[t];
        c.triangles.push_back(t);
        for (uint32_t v : part.triangles[t]) {
            const auto uv = project(part.positions[v], label[t]);
            c.u0 = std::min(c.u0, uv[0]), c.u1 = std::max(c.u1, uv[0]);
            c.v0 = std::min(c.v0, uv[1]), c.v1 = std::max(c.v1, uv[1]);
        }
    }
    std::vector<Chart*> order;
    double area = 0;
    for (auto& [root, c] : byRoot) {
        order.push_back(&c);
        area += (c.u1 - c.u0) * (c.v1 - c.v0);
    }
    // Tallest first (ties by width, then by first triangle: deterministic).
    std::stable_sort(order.begin(), order.end(),
                     [](const Chart* a, const Chart* b) { return a->v1 - a->v0 > b->v1 - b->v0; });
    double longest = 0;
    for (const Chart* c : order) longest = std::max({longest, c->u1 - c->u0, c->v1 - c->v0});
    // The square's side: from the charts' area up, 3 % at a time, until they fit with their
    // gutters (a gutter of g uv units is g * side metres).
    double side = std::max(std::sqrt(std::max(area, 1e-30)), longest);
    for (int i = 0; i < 1000 && !pack(order, side, gutter * side); ++i) side *= 1.03;

    PartCharts out;
    out.charts = static_cast<int>(order.size());
    out.metresPerUv = side;
    for (const Chart* c : order) {
        std::unordered_map<uint32_t, uint32_t> vertexInChart;  // a chart's own vertices
        for (size_t t : c->triangles) {
            std::array<uint32_t, 3> tri;
            for (int k = 0; k < 3; ++k) {
                const uint32_t v = part.triangles[t][k];
                auto [it, isNew] =
                    vertexInChart.try_emplace(v, static_cast<uint32_t>(out.mesh.positions.size()));
                if (isNew) {
                    const auto uv = project(part.positions[v], c->projection);
                    out.mesh.positions.push_back(part.positions[v]);
                    if (!part.normals.empty()) out.mesh.normals.push_back(part.normals[v]);
                    out.mesh.uvs.push_back(
                        {(uv[0] - c->u0 + c->x) / side, (uv[1] - c->v0 + c->y) / side});
                }
                tri[k] = it->second;
            }
            out.mesh.triangles.push_back(tri);
        }
    }
    return out;
}

}  // namespace nenrin
