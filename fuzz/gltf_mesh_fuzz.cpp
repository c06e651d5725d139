// glTF 2.0 meshes (docs/scene-format.md, "mesh"): .gltf or .glb (sniffed by its magic), read
// with tinygltf and our accessor checks; every vertex checked.
#include <cmath>

#include "fuzz/fuzz_input.h"
#include "renderer/geometry/gltf_mesh.h"
#include "util/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace nenrin;
    try {
        TriangleMesh mesh = loadGltfMesh(fuzz::writeInputFile(data, size, ".gltf"));
        for (const Vec3& p : mesh.positions)
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                fuzz::fail("a non-finite vertex");
        for (const auto& t : mesh.triangles)
            for (uint32_t v : t)
                if (v >= mesh.positions.size()) fuzz::fail("an index past the vertices");
        if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size())
            fuzz::fail("uvs and positions differ in number");
    } catch (const InputError&) {
    }
    return 0;
}
