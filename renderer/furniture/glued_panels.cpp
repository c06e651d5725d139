#include "renderer/furniture/glued_panels.h"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <tuple>

namespace nenrin {

namespace {

/// Builds the clipped mesh: original vertices and edge crossings each added once.
class SlabMesh {
public:
    explicit SlabMesh(const TriangleMesh& in) : in_(in) {}

    uint32_t original(uint32_t v) {
        auto [it, isNew] = originals_.try_emplace(v, uint32_t(out.positions.size()));
        if (isNew) push(v, v, 0);
        return it->second;
    }
    /// Where edge (a, b) crosses the plane s = c: computed from the lower index, so the two
    /// triangles sharing the edge get the same vertex.
    uint32_t crossing(uint32_t a, uint32_t b, int plane, double sa, double sb, double c) {
        if (a > b) {
            std::swap(a, b);
            std::swap(sa, sb);
        }
        auto [it, isNew] = crossings_.try_emplace({a, b, plane}, uint32_t(out.positions.size()));
        if (isNew) push(a, b, (c - sa) / (sb - sa));
        return it->second;
    }

    TriangleMesh out;

private:
    void push(uint32_t a, uint32_t b, double t) {
        out.positions.push_back(in_.positions[a] * (1 - t) + in_.positions[b] * t);
        if (!in_.normals.empty()) {
            const Vec3 n = in_.normals[a] * (1 - t) + in_.normals[b] * t;
            out.normals.push_back(lengthSquared(n) > 0 ? normalize(n) : in_.normals[a]);
        }
        if (!in_.uvs.empty())
            out.uvs.push_back({in_.uvs[a][0] * (1 - t) + in_.uvs[b][0] * t,
                               in_.uvs[a][1] * (1 - t) + in_.uvs[b][1] * t});
    }

    const TriangleMesh& in_;
    std::map<uint32_t, uint32_t> originals_;
    std::map<std::tuple<uint32_t, uint32_t, int>, uint32_t> crossings_;
};

}  // namespace

TriangleMesh clipToSlab(const TriangleMesh& mesh, const Vec3& origin, const Vec3& axis, double lo,
                        double hi) {
    SlabMesh slab(mesh);
    const double planes[2] = {lo, hi};
    for (const auto& tri : mesh.triangles) {
        double s[3];
        for (int i = 0; i < 3; ++i) s[i] = dot(mesh.positions[tri[i]] - origin, axis);
        // The slab cuts a triangle into a convex polygon whose corners are the triangle's
        // corners inside the slab and its edges' crossings of the two planes, in the order a
        // walk round the triangle meets them.
        std::vector<uint32_t> polygon;
        for (int i = 0; i < 3; ++i) {
            const int j = (i + 1) % 3;
            if (s[i] >= lo && s[i] <= hi) polygon.push_back(slab.original(tri[i]));
            int order[2] = {0, 1};  // the planes in the order the edge meets them
            if (s[j] < s[i]) std::swap(order[0], order[1]);
            for (int k : order) {
                const double c = planes[k];
                if ((s[i] - c) * (s[j] - c) < 0)
                    polygon.push_back(slab.crossing(tri[i], tri[j], k, s[i], s[j], c));
            }
        }
        for (size_t k = 2; k < polygon.size(); ++k)
            slab.out.triangles.push_back({polygon[0], polygon[k - 1], polygon[k]});
    }
    return std::move(slab.out);
}

std::vector<ModelPart> glueWidePanels(std::vector<ModelPart> parts,
                                      const std::map<std::string, PartChoice>& choices) {
    std::vector<ModelPart> out;
    for (ModelPart& part : parts) {
        const PartChoice choice = choiceFor(part, choices);
        const PartFrame frame = plannedFrame(part, choice);
        const int boards = int(std::ceil(frame.extent.y / kWidestBoard - 1e-9));
        if (!choice.wood.value_or(true) || !(part.area > 0) || boards <= 1) {
            out.push_back(std::move(part));
            continue;
        }
        const double width = frame.extent.y / boards;
        for (int k = 0; k < boards; ++k) {
            // The outermost planes lie well outside, so no sliver of the part is lost.
            const double lo = k == 0 ? -frame.extent.y : -0.5 * frame.extent.y + k * width;
            const double hi =
                k == boards - 1 ? frame.extent.y : -0.5 * frame.extent.y + (k + 1) * width;
            ModelPart board;
            board.mesh = clipToSlab(part.mesh, frame.centre, frame.axes[1], lo, hi);
            board.area = surfaceArea(board.mesh);
            if (board.mesh.triangles.empty()) continue;
            board.name = fmt::format("{}/board-{}", part.name, k + 1);
            board.material = part.material;
            board.panel = part.name;
            board.panelFibre = frame.axes[0];
            board.panelBoard = k + 1;
            out.push_back(std::move(board));
        }
    }
    return out;
}

}  // namespace nenrin
