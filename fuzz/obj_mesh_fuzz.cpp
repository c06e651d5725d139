// Wavefront OBJ meshes (docs/scene-format.md, "mesh"): read, every vertex checked.
#include <cmath>

#include "fuzz/fuzz_input.h"
#include "renderer/geometry/obj_mesh.h"
#include "util/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace nenrin;
    try {
        TriangleMesh mesh = loadObjMesh(fuzz::writeInputFile(data, size, ".obj"));
        for (const Vec3& p : mesh.positions)
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                fuzz::fail("a non-finite vertex");
    } catch (const InputError&) {
    }
    return 0;
}
