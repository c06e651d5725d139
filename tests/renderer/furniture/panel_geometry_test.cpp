// The geometry nenrin furniture adds to a model: wide panels cut into the boards they are
// glued from (clipping a mesh to slabs) and normals for models without any (smooth across
// gentle angles, sharp at a board's edges).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>

#include "renderer/furniture/crease_normals.h"
#include "renderer/furniture/glued_panels.h"
#include "renderer/furniture/welded_vertices.h"

namespace nenrin {
namespace {

/// A closed box centred at the origin, 8 shared corners, wound outwards.
TriangleMesh box(const Vec3& size) {
    TriangleMesh m;
    for (int i = 0; i < 8; ++i)
        m.positions.push_back({(i & 1 ? 0.5 : -0.5) * size.x, (i & 2 ? 0.5 : -0.5) * size.y,
                               (i & 4 ? 0.5 : -0.5) * size.z});
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
        m.triangles.push_back({uint32_t(q[0]), uint32_t(q[1]), uint32_t(q[2])});
        m.triangles.push_back({uint32_t(q[0]), uint32_t(q[2]), uint32_t(q[3])});
    }
    return m;
}

double signedVolume(const TriangleMesh& m) {
    double v = 0;
    for (const auto& t : m.triangles)
        v += dot(m.positions[t[0]], cross(m.positions[t[1]], m.positions[t[2]])) / 6;
    return v;
}

TEST(PanelGeometry, SlabsCutAMeshWithoutLosingOrAddingSurface) {
    const TriangleMesh b = box({0.6, 0.45, 0.03});
    const Vec3 axis = normalize(Vec3{0.2, 1, 0.1});  // oblique: every triangle crossed
    double total = 0;
    for (int k = 0; k < 3; ++k) {
        const double lo = -0.3 + 0.2 * k, hi = lo + 0.2;
        const TriangleMesh s = clipToSlab(b, {}, axis, lo, hi);
        total += surfaceArea(s);
        for (const Vec3& p : s.positions) {
            EXPECT_GE(dot(p, axis), lo - 1e-12);
            EXPECT_LE(dot(p, axis), hi + 1e-12);
        }
        // Winding kept: the piece's open surface encloses a positive volume about the origin
        // only in part, but no triangle is turned over (each faces the box's own way).
        for (const auto& t : s.triangles) {
            const Vec3 n =
                cross(s.positions[t[1]] - s.positions[t[0]], s.positions[t[2]] - s.positions[t[0]]);
            const Vec3 c = (s.positions[t[0]] + s.positions[t[1]] + s.positions[t[2]]) / 3;
            // The box's face the triangle lies on: its outward normal is the largest
            // coordinate relative to the half size.
            const Vec3 half{0.3, 0.225, 0.015};
            const double rx = std::abs(c.x) / half.x, ry = std::abs(c.y) / half.y,
                         rz = std::abs(c.z) / half.z;
            const Vec3 outward = rx >= ry && rx >= rz   ? Vec3{c.x > 0 ? 1.0 : -1.0, 0, 0}
                                 : ry >= rx && ry >= rz ? Vec3{0, c.y > 0 ? 1.0 : -1.0, 0}
                                                        : Vec3{0, 0, c.z > 0 ? 1.0 : -1.0};
            EXPECT_GT(dot(n, outward), 0);
        }
        // Vertices on a shared edge are shared: no two at one position.
        const std::vector<uint32_t> ids = weldedVertexIds(s);
        EXPECT_EQ(std::set<uint32_t>(ids.begin(), ids.end()).size(), s.positions.size());
    }
    EXPECT_NEAR(total, surfaceArea(b), 1e-12);
    EXPECT_GT(signedVolume(b), 0);
}

TEST(PanelGeometry, AWidePanelIsGluedFromBoardsAlongItsFibre) {
    ModelPart seat;
    seat.name = "seat";
    seat.material = "oak";
    seat.mesh = box({0.5, 0.03, 0.42});  // fibre along x, 42 cm wide along z
    seat.area = surfaceArea(seat.mesh);
    ModelPart leg;
    leg.name = "leg";
    leg.mesh = box({0.04, 0.45, 0.04});
    leg.area = surfaceArea(leg.mesh);
    std::vector<ModelPart> parts = glueWidePanels({seat, leg}, {});
    ASSERT_EQ(parts.size(), 4u);  // ceil(0.42 / 0.2) = 3 boards, and the leg
    double boards = 0;
    for (int k = 0; k < 3; ++k) {
        const ModelPart& p = parts[k];
        EXPECT_EQ(p.name, "seat/board-" + std::to_string(k + 1));
        EXPECT_EQ(p.panel, "seat");
        EXPECT_EQ(p.panelBoard, k + 1);
        EXPECT_EQ(p.material, "oak");
        ASSERT_TRUE(p.panelFibre);
        EXPECT_NEAR(std::abs(p.panelFibre->x), 1, 1e-9);
        double lo = 1, hi = -1;
        for (const Vec3& v : p.mesh.positions) {
            lo = std::min(lo, v.z);
            hi = std::max(hi, v.z);
        }
        EXPECT_NEAR(hi - lo, 0.14, 1e-9);
        // Each board keeps the panel's fibre although it is nearly square-ish in plan.
        const PartFrame f = plannedFrame(p, choiceFor(p, {}));
        EXPECT_NEAR(std::abs(f.axes[0].x), 1, 1e-9);
        boards += p.area;
    }
    EXPECT_NEAR(boards, seat.area, 1e-12);
    EXPECT_EQ(parts[3].name, "leg");
    EXPECT_TRUE(parts[3].panel.empty());
    // Marked not wood (an upholstered seat), the panel is left whole.
    PartChoice notWood;
    notWood.wood = false;
    EXPECT_EQ(glueWidePanels({seat}, {{"seat", notWood}}).size(), 1u);
    // A seed chosen for the panel numbers its boards.
    PartChoice seeded;
    seeded.seed = 40;
    EXPECT_EQ(*choiceFor(parts[2], {{"seat", seeded}}).seed, 42u);
}

TEST(PanelGeometry, CreaseNormalsAreSharpAtEdgesAndSmoothOnCurves) {
    // A box: every corner splits into its three faces' normals.
    const TriangleMesh b = withCreaseNormals(box({1, 2, 3}));
    EXPECT_EQ(b.positions.size(), 24u);
    for (size_t v = 0; v < b.positions.size(); ++v) {
        const Vec3& n = b.normals[v];
        EXPECT_NEAR(std::abs(n.x) + std::abs(n.y) + std::abs(n.z), 1, 1e-12);
        const Vec3& p = b.positions[v];
        EXPECT_GT(dot(n, p), 0);  // outward
    }
    // A 24-sided cylinder (15 degrees between facets): smooth, normals radial.
    TriangleMesh c;
    const int sides = 24;
    for (int i = 0; i < sides; ++i) {
        const double a = 2 * std::numbers::pi * i / sides;
        c.positions.push_back({std::cos(a), std::sin(a), 0});
        c.positions.push_back({std::cos(a), std::sin(a), 1});
    }
    for (int i = 0; i < sides; ++i) {
        const uint32_t a = 2 * i, b2 = 2 * ((i + 1) % sides);
        c.triangles.push_back({a, b2, b2 + 1});
        c.triangles.push_back({a, b2 + 1, a + 1});
    }
    const TriangleMesh s = withCreaseNormals(c);
    EXPECT_EQ(s.positions.size(), c.positions.size());
    for (size_t v = 0; v < s.positions.size(); ++v) {
        const Vec3 radial = normalize(Vec3{s.positions[v].x, s.positions[v].y, 0});
        EXPECT_GT(dot(s.normals[v], radial), std::cos(1e-6)) << v;
    }
}

}  // namespace
}  // namespace nenrin
