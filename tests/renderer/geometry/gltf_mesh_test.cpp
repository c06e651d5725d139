// The glTF mesh reader: node transforms, the uv convention, and bad files refused with the
// place named.

#include "renderer/geometry/gltf_mesh.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

#include "util/input_error.h"

namespace nenrin {
namespace {

const std::string kData = std::string(NENRIN_SOURCE_DIR) + "/tests/data/";

TEST(GltfMesh, AppliesTheNodeTreeAndFlipsV) {
    // A unit quad scaled by 2 in the child node and moved by (1, 0, 0) in its parent.
    TriangleMesh m = loadGltfMesh(kData + "meshes/quad-nodes.gltf");
    ASSERT_EQ(m.positions.size(), 4u);
    ASSERT_EQ(m.triangles.size(), 2u);
    ASSERT_EQ(m.uvs.size(), 4u);
    ASSERT_EQ(m.normals.size(), 4u);
    const Vec3 expected[4] = {{1, 0, 0}, {3, 0, 0}, {3, 2, 0}, {1, 2, 0}};
    for (int i = 0; i < 4; ++i) {
        EXPECT_DOUBLE_EQ(m.positions[i].x, expected[i].x) << i;
        EXPECT_DOUBLE_EQ(m.positions[i].y, expected[i].y) << i;
        EXPECT_DOUBLE_EQ(m.positions[i].z, expected[i].z) << i;
        EXPECT_DOUBLE_EQ(m.normals[i].z, 1) << i;
    }
    // The file's uvs are OBJ's (0,0), (1,0), (1,1), (0,1) with v running down the image.
    EXPECT_DOUBLE_EQ(m.uvs[0][1], 0);
    EXPECT_DOUBLE_EQ(m.uvs[2][0], 1);
    EXPECT_DOUBLE_EQ(m.uvs[2][1], 1);
    // Winding kept (counter-clockwise seen from +z, as the normals say).
    Vec3 n = cross(m.positions[m.triangles[0][1]] - m.positions[m.triangles[0][0]],
                   m.positions[m.triangles[0][2]] - m.positions[m.triangles[0][0]]);
    EXPECT_GT(n.z, 0);
}

void expectError(const std::string& file, const std::string& fragment) {
    try {
        loadGltfMesh(kData + file);
        ADD_FAILURE() << file << " loaded";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(file.substr(file.find('/') + 1)), std::string::npos)
            << e.what();
    }
}

TEST(GltfMesh, RefusesBadFilesNamingThePlace) {
    expectError("bad/quad-index-out-of-range.gltf", "index 9 (triangle 0) is past the 4 vertices");
    expectError("bad/quad-view-past-buffer.gltf", "accessor 0");
    expectError("bad/README.md", "tinygltf cannot read");
    expectError("scenes/uv-cube.json", "tinygltf cannot read the file");  // JSON, not glTF
}

TEST(GltfMesh, FloatIndicesAreRefused) {
    // Found by fuzzing (fuzz/regressions/gltf_mesh): a baked cube whose index accessor was
    // turned into floats, one of them -2.9e36 (once cast to an unsigned index: UB).
    const std::string file =
        std::string(NENRIN_SOURCE_DIR) + "/fuzz/regressions/gltf_mesh/float-indices.glb";
    try {
        loadGltfMesh(file);
        ADD_FAILURE() << "float indices were read";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("expected unsigned byte, short or int indices"),
                  std::string::npos)
            << e.what();
    }
}

TEST(GltfMesh, ABufferThatIsADeviceIsRefused) {
    // The quad with its buffer pointing at /dev/zero (which would read forever).
    std::string text;
    {
        std::ifstream in(kData + "meshes/quad-nodes.gltf");
        text.assign(std::istreambuf_iterator<char>(in), {});
    }
    size_t at = text.find("data:application/octet-stream;base64,");
    ASSERT_NE(at, std::string::npos);
    size_t end = text.find('"', at);
    text.replace(at, end - at, "../../../../../../../../../../dev/zero");
    const std::string path = ::testing::TempDir() + "/nenrin-device-buffer.gltf";
    std::ofstream(path) << text;
    try {
        loadGltfMesh(path);
        ADD_FAILURE() << "a device buffer was read";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
    }
    std::remove(path.c_str());
}

TEST(GltfMesh, ABufferNameTheSystemRefusesIsAnInputError) {
    // A 300-character folder name (over the 255 a name may have): the system answers "name too
    // long", which once escaped as a std::filesystem error (found by fuzz_gltf_mesh).
    const std::string path = ::testing::TempDir() + "/nenrin-long-buffer-name.gltf";
    std::ofstream(path) << R"({"asset": {"version": "2.0"}, "buffers": [{"uri": ")"
                        << std::string(300, 'b') << R"(/x.bin", "byteLength": 12}]})";
    EXPECT_THROW(loadGltfMesh(path), InputError);
    std::remove(path.c_str());
}

TEST(GltfMesh, RecognisesTheExtensions) {
    EXPECT_TRUE(isGltfPath("a/b.gltf"));
    EXPECT_TRUE(isGltfPath("B.GLB"));
    EXPECT_FALSE(isGltfPath("b.obj"));
    EXPECT_FALSE(isGltfPath("gltf"));
}

}  // namespace
}  // namespace nenrin
