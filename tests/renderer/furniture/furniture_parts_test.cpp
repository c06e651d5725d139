// Furniture parts: a model's groups split into connected pieces, each piece's principal frame
// (fibre along the longest axis), the sawing a board shows, and a scene's log angles.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>

#include "renderer/furniture/furniture_plan.h"
#include "renderer/furniture/model_parts.h"
#include "renderer/furniture/part_charts.h"
#include "renderer/furniture/part_frame.h"
#include "renderer/geometry/gltf_mesh.h"
#include "renderer/jobs/furniture_job.h"
#include "renderer/scene_file.h"
#include "renderer/texture_set/uv_raster.h"
#include "tests/scratch_path.h"
#include "util/json_parse.h"

namespace nenrin {
namespace {

/// Appends a closed box (12 triangles) of `size`, turned and placed by `turn`, in group
/// `group`.
void addBox(TriangleMesh& m, const Vec3& size, const RigidTransform& turn, uint32_t group) {
    const uint32_t first = static_cast<uint32_t>(m.positions.size());
    for (int i = 0; i < 8; ++i)
        m.positions.push_back(
            turn.point({(i & 1 ? 0.5 : -0.5) * size.x, (i & 2 ? 0.5 : -0.5) * size.y,
                        (i & 4 ? 0.5 : -0.5) * size.z}));
    const int quads[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                             {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
    // Wound counter-clockwise seen from outside (normals outward), as a closed model is.
    auto outward = [&](std::array<uint32_t, 3> t) {
        const Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
        if (dot(cross(b - a, c - a), (a + b + c) * (1.0 / 3) - turn.origin) < 0)
            std::swap(t[1], t[2]);
        return t;
    };
    for (const auto& q : quads) {
        m.triangles.push_back(outward({first + q[0], first + q[1], first + q[2]}));
        m.triangles.push_back(outward({first + q[0], first + q[2], first + q[3]}));
        m.triangleGroups.push_back(group);
        m.triangleGroups.push_back(group);
        m.triangleMaterials.push_back(0);
        m.triangleMaterials.push_back(0);
    }
}

TriangleMesh emptyModel() {
    TriangleMesh m;
    m.groupNames = {"legs", "seat"};
    m.materialNames = {"oak"};
    return m;
}

TEST(FurnitureParts, GroupsSplitIntoTheirConnectedPieces) {
    TriangleMesh m = emptyModel();
    // Two legs in one group, apart; a seat touching one of them (sharing no vertex).
    addBox(m, {0.04, 0.5, 0.04}, RigidTransform::translation({0, 0.25, 0}), 0);
    addBox(m, {0.04, 0.5, 0.04}, RigidTransform::translation({0.4, 0.25, 0}), 0);
    addBox(m, {0.5, 0.03, 0.4}, RigidTransform::translation({0.2, 0.515, 0}), 1);
    const std::vector<ModelPart> parts = splitModelParts(m, "model.obj");
    ASSERT_EQ(parts.size(), 3u);
    EXPECT_EQ(parts[0].name, "legs.1");
    EXPECT_EQ(parts[1].name, "legs.2");
    EXPECT_EQ(parts[2].name, "seat");
    EXPECT_EQ(parts[2].material, "oak");
    for (const ModelPart& p : parts) EXPECT_EQ(p.mesh.triangles.size(), 12u);
    EXPECT_NEAR(parts[2].area, 2 * (0.5 * 0.03 + 0.5 * 0.4 + 0.03 * 0.4), 1e-12);
}

TEST(FurnitureParts, VerticesAtOnePositionJoinAPiece) {
    // A box whose faces each have their own four vertices (split at uv seams, as loaders do)
    // is one piece.
    TriangleMesh m = emptyModel();
    addBox(m, {0.1, 0.2, 0.3}, {}, 0);
    TriangleMesh split = m;
    split.positions.clear();
    for (auto& t : split.triangles)
        for (uint32_t& v : t) {
            split.positions.push_back(m.positions[v]);
            v = static_cast<uint32_t>(split.positions.size() - 1);
        }
    EXPECT_EQ(splitModelParts(split, "model.obj").size(), 1u);
}

TEST(FurnitureParts, TheFibreRunsAlongThePartsLongestAxis) {
    // A rail 0.6 x 0.08 x 0.02 turned 30 degrees about z and 20 about x: its frame is the
    // turned x, y, z axes, its extent the rail's size.
    TriangleMesh m = emptyModel();
    const RigidTransform turn = RigidTransform::rotation({1, 0, 0}, radians(20)) *
                                RigidTransform::rotation({0, 0, 1}, radians(30));
    RigidTransform placed = turn;
    placed.origin = {0.3, 0.7, -0.1};
    addBox(m, {0.6, 0.08, 0.02}, placed, 0);
    const PartFrame f = partFrame(m);
    EXPECT_NEAR(std::abs(dot(f.axes[0], turn.x)), 1, 1e-9);
    EXPECT_NEAR(std::abs(dot(f.axes[1], turn.y)), 1, 1e-9);
    EXPECT_NEAR(std::abs(dot(f.axes[2], turn.z)), 1, 1e-9);
    EXPECT_NEAR(f.extent.x, 0.6, 1e-9);
    EXPECT_NEAR(f.extent.y, 0.08, 1e-9);
    EXPECT_NEAR(f.extent.z, 0.02, 1e-9);
    EXPECT_NEAR(length(f.centre - placed.origin), 0, 1e-9);
    // The fibre given: the width axis is the principal axis most across it.
    const PartFrame along = partFrameAlong(m, turn.y);
    EXPECT_NEAR(std::abs(dot(along.axes[0], turn.y)), 1, 1e-12);
    EXPECT_NEAR(std::abs(dot(along.axes[1], turn.x)), 1, 1e-9);
    EXPECT_NEAR(along.extent.x, 0.08, 1e-9);
}

TEST(FurnitureParts, SawingIsTheRingsAngleToTheWideFace) {
    // A board 10 cm from the pith along +x: its wide face normal (lamella z) along the radius
    // is flat-sawn, across it quarter-sawn, 45 degrees between rift-sawn.
    auto board = [](double normalAngleDegrees) {
        const Vec3 n{std::cos(radians(normalAngleDegrees)), std::sin(radians(normalAngleDegrees)),
                     0};
        const Vec3 length{0, 0, 1};
        return RigidTransform::fromAxes(length, cross(n, length), n, {0.1, 0, 1});
    };
    EXPECT_EQ(sawingAsCut(board(0)), "flat");
    EXPECT_EQ(sawingAsCut(board(20)), "flat");
    EXPECT_EQ(sawingAsCut(board(45)), "rift");
    EXPECT_EQ(sawingAsCut(board(75)), "quarter");
    EXPECT_EQ(sawingAsCut(board(90)), "quarter");
}

TEST(FurnitureParts, LogAnglesGiveBackTheTransform) {
    // The scene's log.rotate (x, then y, then z, then stood on the trunk) rebuilt from the
    // angles equals the rotation they were taken from.
    const RigidTransform standing =
        RigidTransform::fromAxes({1, 0, 0}, {0, 0, 1}, {0, -1, 0}, {0, 0, 0});
    for (int k = 0; k < 50; ++k) {
        const RigidTransform r =
            RigidTransform::rotation(normalize(Vec3{std::sin(k * 1.3), std::cos(k * 0.7), 0.4}),
                                     0.37 * k) *
            (k % 7 == 0 ? RigidTransform::rotation({0, 1, 0}, radians(90)) : RigidTransform{});
        const Vec3 a = logRotateDegrees(r);
        const RigidTransform back = standing * RigidTransform::rotation({0, 0, 1}, radians(a.z)) *
                                    RigidTransform::rotation({0, 1, 0}, radians(a.y)) *
                                    RigidTransform::rotation({1, 0, 0}, radians(a.x));
        EXPECT_NEAR(length(back.x - r.x) + length(back.y - r.y) + length(back.z - r.z), 0, 1e-9)
            << k;
    }
}

// Charts for a part without usable uvs: a rail (box) turned in space gets one chart per
// face, packed inside the unit square without overlap, at one scale (uv area = surface area /
// side^2), every chart the surface's way round, u along the fibre on the long faces.
TEST(FurnitureParts, ChartsCoverThePartOnceAtOneScale) {
    TriangleMesh m = emptyModel();
    RigidTransform turn = RigidTransform::rotation(normalize(Vec3{1, 2, 3}), 0.7);
    turn.origin = {0.1, 0.4, -0.2};
    addBox(m, {0.6, 0.08, 0.03}, turn, 0);
    const PartFrame frame = partFrame(m);
    const double gutter = 4.0 / 1024;
    const PartCharts c = chartPart(m, frame, gutter);
    EXPECT_EQ(c.charts, 6);
    ASSERT_EQ(c.mesh.triangles.size(), 12u);
    ASSERT_EQ(c.mesh.uvs.size(), c.mesh.positions.size());
    const Vec3 centre = turn.origin;
    double uvArea = 0;
    for (const auto& t : c.mesh.triangles) {
        const auto& a = c.mesh.uvs[t[0]];
        const auto& b = c.mesh.uvs[t[1]];
        const auto& d = c.mesh.uvs[t[2]];
        const double signedUv =
            0.5 * ((b[0] - a[0]) * (d[1] - a[1]) - (d[0] - a[0]) * (b[1] - a[1]));
        const Vec3 p0 = c.mesh.positions[t[0]], p1 = c.mesh.positions[t[1]],
                   p2 = c.mesh.positions[t[2]];
        const Vec3 e = cross(p1 - p0, p2 - p0);
        // The same way round in uv as seen from outside.
        const double outward = dot(e, (p0 + p1 + p2) * (1.0 / 3) - centre);
        EXPECT_GT(signedUv * outward, 0);
        EXPECT_NEAR(std::abs(signedUv) * c.metresPerUv * c.metresPerUv, 0.5 * length(e), 1e-12);
        uvArea += std::abs(signedUv);
        for (const auto* uv : {&a, &b, &d})
            for (double x : *uv) {
                EXPECT_GE(x, gutter * 0.999);
                EXPECT_LE(x, 1 - gutter * 0.999);
            }
        // On the long faces (normal across the fibre) u runs along the fibre.
        const Vec3 n = normalize(e);
        if (std::abs(dot(n, frame.axes[0])) < 0.5 && std::abs(b[0] - a[0]) > 1e-9) {
            const double du = b[0] - a[0];
            EXPECT_NEAR(std::abs(dot(p1 - p0, frame.axes[0])), std::abs(du) * c.metresPerUv, 1e-9);
        }
    }
    // Six faces' rectangles inside the square, none overlapping: their total area is the
    // surface's and below the square's.
    EXPECT_NEAR(uvArea * c.metresPerUv * c.metresPerUv, 2 * (0.6 * 0.08 + 0.6 * 0.03 + 0.08 * 0.03),
                1e-9);
    EXPECT_LT(uvArea, 1);
}

std::string base64(const std::string& bytes) {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
        if (i + 2 < bytes.size()) v |= uint8_t(bytes[i + 2]);
        out += k[(v >> 18) & 63];
        out += k[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? k[(v >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? k[v & 63] : '=';
    }
    return out;
}

// A glTF model of one rail mesh placed by two nodes, the second turned 90 degrees about z:
// two parts, the turned one with its fibre turned with it (along y, not x).
TEST(FurnitureParts, GltfNodeTransformsTurnTheirPartsFibre) {
    namespace fs = std::filesystem;
    std::string buffer;
    auto put = [&](const void* p, size_t n) { buffer.append(static_cast<const char*>(p), n); };
    for (int i = 0; i < 8; ++i) {
        const float v[3] = {i & 1 ? 0.25f : -0.25f, i & 2 ? 0.02f : -0.02f, i & 4 ? 0.03f : -0.03f};
        put(v, sizeof v);
    }
    const uint16_t quads[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                                  {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
    for (const auto& q : quads) {
        const uint16_t tris[6] = {q[0], q[1], q[2], q[0], q[2], q[3]};
        put(tris, sizeof tris);
    }
    const double h = std::sqrt(0.5);
    const nlohmann::json gltf = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0, 1}}}}},
        {"nodes",
         {{{"mesh", 0}, {"name", "rail"}},
          {{"mesh", 0},
           {"name", "turned"},
           {"translation", {0, 0.5, 0}},
           {"rotation", {0, 0, h, h}}}}},
        {"meshes",
         {{{"name", "rail"},
           {"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
        {"buffers",
         {{{"byteLength", buffer.size()},
           {"uri", "data:application/octet-stream;base64," + base64(buffer)}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 96}},
          {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 72}}}},
        {"accessors",
         {{{"bufferView", 0},
           {"componentType", 5126},
           {"count", 8},
           {"type", "VEC3"},
           {"min", {-0.25, -0.02, -0.03}},
           {"max", {0.25, 0.02, 0.03}}},
          {{"bufferView", 1}, {"componentType", 5123}, {"count", 36}, {"type", "SCALAR"}}}}};
    const fs::path file = scratchPath("furniture-test-rails.gltf");
    std::ofstream(file) << gltf.dump();
    const std::vector<ModelPart> parts =
        splitModelParts(loadFurnitureModel(file.string(), 1.0), file.string());
    // One node alone (a scene's mesh object with "node"), with its transform.
    const TriangleMesh turned = loadGltfMesh(file.string(), "turned");
    EXPECT_EQ(turned.triangles.size(), 12u);
    EXPECT_NEAR(partFrame(turned).centre.y, 0.5, 1e-6);
    EXPECT_THROW(loadGltfMesh(file.string(), "seat"), InputError);
    fs::remove(file);
    ASSERT_EQ(parts.size(), 2u);
    EXPECT_EQ(parts[0].name, "rail");
    EXPECT_EQ(parts[1].name, "rail.1");  // the mesh's second instance
    EXPECT_NEAR(std::abs(partFrame(parts[0].mesh).axes[0].x), 1, 1e-6);
    EXPECT_NEAR(std::abs(partFrame(parts[1].mesh).axes[0].y), 1, 1e-6);
    EXPECT_NEAR(partFrame(parts[1].mesh).centre.y, 0.5, 1e-6);
}

// The scene nenrin furniture writes puts every part of the chair exactly where parts.json
// says it lies in the log (log.position and log.rotate read back by the scene loader).
TEST(FurnitureJob, TheSceneHoldsEveryPartWhereThePlanSays) {
    namespace fs = std::filesystem;
    const fs::path out = scratchPath("furniture-test-scene");
    fs::remove_all(out);
    FurnitureJob job;
    job.model = std::string(NENRIN_SOURCE_DIR) + "/tests/data/furniture/oak-chair/oakChair.obj";
    job.grain = std::string(NENRIN_SOURCE_DIR) + "/scenes/grain/species/european-oak.json";
    job.output = out.string();
    job.unit = "cm";
    job.previewWidth = 32, job.previewHeight = 24, job.previewSpp = 1;
    job.textureSize = 0;
    job.quiet = true;
    runFurnitureJob(job);
    const nlohmann::json plan = parseJsonFile((out / "parts.json").string());
    const std::unique_ptr<Scene> scene = loadScene((out / "scene.json").string());
    size_t checked = 0;
    std::set<double> tints;
    for (const SceneObject& o : scene->objects) {
        for (const auto& p : plan["parts"]) {
            if (p["name"] != o.name) continue;
            auto v = [&](const char* k) {
                const auto& a = p["tree_from_model"][k];
                return Vec3{a[0].get<double>(), a[1].get<double>(), a[2].get<double>()};
            };
            const RigidTransform& t = o.treeFromObject;
            EXPECT_NEAR(length(t.x - v("x")) + length(t.y - v("y")) + length(t.z - v("z")), 0, 1e-9)
                << o.name;
            EXPECT_NEAR(length(t.origin - v("origin")), 0, 1e-12) << o.name;
            // Its board's tree tint, on the object.
            const auto& tint = p["board"]["tint"];
            EXPECT_EQ(o.boardTint.r, tint[0].get<double>()) << o.name;
            EXPECT_EQ(o.boardTint.b, tint[2].get<double>()) << o.name;
            tints.insert(o.boardTint.r);
            ++checked;
        }
    }
    EXPECT_EQ(checked, 19u);       // 17 pieces, the seat glued from three boards
    EXPECT_GT(tints.size(), 10u);  // boards from different trees differ
    // The chair's own uvs are degenerate (a face's corners share one vt): every part got
    // charts of its own, which cover it once (no texel claimed twice, none degenerate).
    for (const auto& p : plan["parts"]) {
        EXPECT_EQ(p["uvs"], "charts") << p["name"];
        const TriangleMesh part = loadObjMesh((out / p["file"].get<std::string>()).string());
        const UvRaster r = rasterizeUv(part, 512, 512);
        EXPECT_EQ(r.overlappingTexels, 0u) << p["name"];
        EXPECT_EQ(r.trianglesOutsideUnitSquare, 0u) << p["name"];
        const std::vector<uint8_t> covered = r.covered();
        EXPECT_GT(std::count(covered.begin(), covered.end(), 1), 512 * 512 / 20) << p["name"];
    }
    fs::remove_all(out);
}

}  // namespace
}  // namespace nenrin
