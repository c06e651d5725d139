#include "renderer/geometry/obj_mesh.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "util/input_error.h"

namespace nenrin {
namespace {

namespace fs = std::filesystem;

// Each test writes its OBJ files into its own directory: ctest runs the cases in parallel.
class ObjMesh : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::path(::testing::TempDir()) /
               ("nenrin-obj-" + std::to_string(getpid()) + "-" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string write(const std::string& name, const std::string& text) {
        std::string path = (dir_ / name).string();
        std::ofstream(path, std::ios::binary) << text;
        return path;
    }
    TriangleMesh load(const std::string& text) { return loadObjMesh(write("m.obj", text)); }
    /// The error for `text`, or a failure when it loads.
    InputError errorOf(const std::string& text) {
        std::string path = write("bad.obj", text);
        try {
            loadObjMesh(path);
        } catch (const InputError& e) {
            return e;
        }
        ADD_FAILURE() << "loaded without an error:\n" << text;
        return InputError("", "", "");
    }

    fs::path dir_;
};

Vec3 faceNormal(const TriangleMesh& m, const std::array<uint32_t, 3>& t) {
    return cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
}

constexpr const char* kCube = R"(# unit cube, outward quads
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 3 4 8 7
f 2 3 7 6
f 4 1 5 8
)";

TEST_F(ObjMesh, UnitCubeOfSixQuadsGivesTwelveOutwardTriangles) {
    TriangleMesh m = load(kCube);
    EXPECT_EQ(m.triangles.size(), 12u);
    EXPECT_EQ(m.positions.size(), 8u);
    EXPECT_TRUE(m.normals.empty());
    EXPECT_TRUE(m.uvs.empty());
    Vec3 lower, upper;
    meshBounds(m, lower, upper);
    EXPECT_EQ(lower, (Vec3{0, 0, 0}));
    EXPECT_EQ(upper, (Vec3{1, 1, 1}));
    // Triangulation keeps each quad's winding: every face normal points away from the centre.
    for (const auto& t : m.triangles) {
        Vec3 centroid = (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) / 3;
        EXPECT_GT(dot(faceNormal(m, t), centroid - Vec3{0.5, 0.5, 0.5}), 0);
    }
}

TEST_F(ObjMesh, QuadWithUvsAndNormalsKeepsThem) {
    TriangleMesh m = load(R"(v -1 -1 0
v 1 -1 0
v 1 1 0
v -1 1 0
vt 0.125 0.25
vt 0.875 0.25
vt 0.875 0.75
vt 0.125 0.75
vn 0 0 2
f 1/1/1 2/2/1 3/3/1 4/4/1
)");
    ASSERT_EQ(m.positions.size(), 4u);
    ASSERT_EQ(m.uvs.size(), 4u);
    ASSERT_EQ(m.normals.size(), 4u);
    EXPECT_EQ(m.triangles.size(), 2u);
    // Vertices in first-seen order, so vertex i is the quad's corner i.
    const std::array<double, 2> uv[] = {{0.125, 0.25}, {0.875, 0.25}, {0.875, 0.75}, {0.125, 0.75}};
    for (size_t i = 0; i < 4; ++i) {
        EXPECT_DOUBLE_EQ(m.uvs[i][0], uv[i][0]) << i;
        EXPECT_DOUBLE_EQ(m.uvs[i][1], uv[i][1]) << i;
        EXPECT_EQ(m.normals[i], (Vec3{0, 0, 1})) << "normals are normalised";
    }
    EXPECT_EQ(m.positions[2], (Vec3{1, 1, 0}));
}

TEST_F(ObjMesh, CornerSharingAPositionWithOtherUvsBecomesItsOwnVertex) {
    const std::string text = R"(v 0 0 0
v 1 0 0
v 1 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0.5 0.5
f 1/1 2/2 3/3
f 1/4 3/3 2/2
)";
    TriangleMesh m = load(text);
    ASSERT_EQ(m.positions.size(), 4u);  // (1,1), (2,2), (3,3) shared; (1,4) is new
    ASSERT_EQ(m.triangles.size(), 2u);
    EXPECT_EQ(m.positions[3], m.positions[0]);
    EXPECT_DOUBLE_EQ(m.uvs[0][0], 0.0);
    EXPECT_DOUBLE_EQ(m.uvs[3][0], 0.5);
    EXPECT_EQ(m.triangles[1], (std::array<uint32_t, 3>{3, 2, 1}));

    TriangleMesh again = load(text);
    EXPECT_EQ(again.positions, m.positions);
    EXPECT_EQ(again.triangles, m.triangles);
}

TEST_F(ObjMesh, MergesObjectsAndGroupsAndIgnoresMaterialsAndCrLf) {
    TriangleMesh m = load(
        "mtllib missing.mtl\r\no first\r\nv 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nv 0 0 1\r\n"
        "usemtl oak\r\nf 1 2 3\r\ng second\r\nusemtl walnut\r\nf 1 2 4\r\no third\r\nf -4 -2 "
        "-1\r\n");
    ASSERT_EQ(m.triangles.size(), 3u);
    EXPECT_EQ(m.triangles[2], (std::array<uint32_t, 3>{0, 2, 3}));
}

TEST_F(ObjMesh, ConcavePolygonIsEarClipped) {
    // An L whose first corner cannot see the whole polygon: a fan from it would fold over.
    TriangleMesh m = load(R"(v 2 0 0
v 2 1 0
v 1 1 0
v 1 2 0
v 0 2 0
v 0 0 0
f 1 2 3 4 5 6
)");
    ASSERT_EQ(m.triangles.size(), 4u);
    double area = 0;
    for (const auto& t : m.triangles) {
        Vec3 n = faceNormal(m, t);
        EXPECT_GT(n.z, 0);
        area += length(n) / 2;
    }
    EXPECT_NEAR(area, 3, 1e-12);
}

TEST_F(ObjMesh, PolygonWithMoreThan255Corners) {
    // tinyobjloader counts a face's corners in an unsigned char.
    std::string text, face = "f";
    for (int i = 0; i < 300; ++i) {
        double a = 2 * std::numbers::pi * i / 300;
        text += fmt::format("v {} 0 {}\n", std::cos(a), -std::sin(a));
        face += fmt::format(" {}", i + 1);
    }
    TriangleMesh m = load(text + face + "\n");
    EXPECT_EQ(m.positions.size(), 300u);
    ASSERT_EQ(m.triangles.size(), 298u);
    for (const auto& t : m.triangles) EXPECT_GT(faceNormal(m, t).y, 0);
}

TEST_F(ObjMesh, MissingFileIsAnInputErrorNamingIt) {
    std::string path = (dir_ / "no-such.obj").string();
    try {
        loadObjMesh(path);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), path);
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
    }
    EXPECT_THROW(loadObjMesh(dir_.string()), InputError);
}

TEST_F(ObjMesh, GarbageAndBadIndicesAreInputErrors) {
    const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    InputError e = errorOf(triangle + "f 1 2 99\n");
    EXPECT_EQ(e.where(), "line 4");
    EXPECT_NE(e.message().find("99"), std::string::npos) << e.what();
    // tinyobjloader itself would drop such a quad with only a warning.
    EXPECT_EQ(errorOf(triangle + "f 1 2 3 4\n").where(), "line 4");
    EXPECT_EQ(errorOf(triangle + "f 1 2 -4\n").where(), "line 4");
    EXPECT_EQ(errorOf(triangle + "vn 0 0 1\nf 1//1 2//1 3//2\n").where(), "line 5");
    EXPECT_EQ(errorOf(triangle + "f 1 0 2\n").where(), "line 4");
    EXPECT_EQ(errorOf(triangle + "f 1 2 x\n").where(), "line 4");
    EXPECT_EQ(errorOf(triangle + "f 1 2\n").where(), "line 4");
    EXPECT_EQ(errorOf("v 0 0 0\nv 1 0 zero\n").where(), "line 2");
    EXPECT_EQ(errorOf(triangle + "vn 0 0 0\nf 1//1 2//1 3//1\n").where(), "line 5");
    errorOf("this is not an OBJ file\njust words\n");
    errorOf("");
    errorOf(triangle);  // no faces
    errorOf(triangle + std::string("f 1 2\0 3\n", 9));
}

TEST_F(ObjMesh, NonFiniteCoordinatesAreInputErrors) {
    for (const char* bad : {"nan", "-inf", "1e39", "1e400"}) {
        InputError e = errorOf(std::string("v 0 0 0\nv 1 ") + bad + " 0\nv 0 1 0\nf 1 2 3\n");
        EXPECT_EQ(e.where(), "line 2") << bad;
        EXPECT_NE(e.message().find(bad), std::string::npos) << e.what();
    }
    EXPECT_EQ(errorOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt nan 0\nf 1/1 2/1 3/1\n").where(), "line 4");
}

TEST_F(ObjMesh, MixedCornersAreInputErrorsNamingTheLine) {
    const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvn 0 0 1\n";
    InputError e = errorOf(head + "f 1/1 2/1 3/1\n\nf 2 4 3\n");
    EXPECT_EQ(e.where(), "line 9");
    EXPECT_NE(e.message().find("line 7"), std::string::npos) << e.what();
    EXPECT_EQ(errorOf(head + "f 1//1 2//1 3/1/1\n").where(), "line 7");
    EXPECT_EQ(errorOf(head + "f 1 2 3\nf 2//1 4//1 3//1\n").where(), "line 8");
}

TEST_F(ObjMesh, ComputedNormalsOfAFlatQuadPointUp) {
    TriangleMesh m = load("v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nf 1 2 3 4\n");
    ASSERT_TRUE(m.normals.empty());
    auto normals = computeVertexNormals(m);
    ASSERT_EQ(normals.size(), 4u);
    for (const Vec3& n : normals) {
        EXPECT_NEAR(n.x, 0, 1e-15);
        EXPECT_NEAR(n.y, 0, 1e-15);
        EXPECT_NEAR(n.z, 1, 1e-15);
    }
}

TEST_F(ObjMesh, ComputedNormalsAreAreaWeightedAndNeverNaN) {
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 1}, {9, 9, 9}, {5, 5, 5}, {7, 7, 7}};
    m.triangles = {{0, 1, 2},   // area 8, +z
                   {0, 3, 1},   // area 2, +y
                   {4, 5, 6},   // collinear: zero area
                   {0, 0, 1}};  // repeated corner: zero area
    auto normals = computeVertexNormals(m);
    ASSERT_EQ(normals.size(), 7u);
    Vec3 expected = normalize(Vec3{0, 2, 8});
    EXPECT_NEAR(length(normals[0] - expected), 0, 1e-12);
    EXPECT_NEAR(length(normals[2] - Vec3{0, 0, 1}), 0, 1e-12);
    for (uint32_t i : {4u, 5u, 6u}) EXPECT_EQ(normals[i], (Vec3{0, 0, 1}));
    for (const Vec3& n : normals) {
        EXPECT_TRUE(isFinite(n));
        EXPECT_NEAR(length(n), 1, 1e-12);
    }
    // Two faces that cancel: the vertex falls back to its first face's normal.
    TriangleMesh sheet;
    sheet.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    sheet.triangles = {{0, 1, 2}, {0, 2, 1}};
    for (const Vec3& n : computeVertexNormals(sheet)) EXPECT_EQ(n, (Vec3{0, 0, 1}));
}

TEST_F(ObjMesh, ShippedTableTopLoads) {
    TriangleMesh m = loadObjMesh(std::string(NENRIN_SOURCE_DIR) + "/scenes/meshes/table-top.obj");
    EXPECT_GE(m.triangles.size(), 1000u);
    EXPECT_LE(m.triangles.size(), 3000u);
    ASSERT_EQ(m.uvs.size(), m.positions.size());
    ASSERT_EQ(m.normals.size(), m.positions.size());
    for (const auto& uv : m.uvs) {
        EXPECT_GE(uv[0], 0);
        EXPECT_LE(uv[0], 1);
        EXPECT_GE(uv[1], 0);
        EXPECT_LE(uv[1], 1);
    }
    Vec3 lower, upper;
    meshBounds(m, lower, upper);
    EXPECT_NEAR(upper.x - lower.x, 1.2, 1e-3);
    EXPECT_NEAR(upper.y - lower.y, 0.03, 1e-3);
    EXPECT_NEAR(upper.z - lower.z, 0.7, 1e-3);
    EXPECT_NEAR(upper.y, 0.015, 1e-3);
    EXPECT_NEAR(length((upper + lower) / 2), 0, 1e-3);
    // Outward winding agrees with the file's normals, and no uv chart is mirrored or folded.
    for (const auto& t : m.triangles) {
        Vec3 n = m.normals[t[0]] + m.normals[t[1]] + m.normals[t[2]];
        EXPECT_GT(dot(faceNormal(m, t), n), 0);
        const auto &a = m.uvs[t[0]], &b = m.uvs[t[1]], &c = m.uvs[t[2]];
        EXPECT_GT((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]), 0);
    }
}

}  // namespace
}  // namespace nenrin
