// Skeleton files (docs/skeleton-format.md): read, then the field grown and shaded from them.
#include "fuzz/fuzz_input.h"
#include "fuzz/wood_probe.h"
#include "skeleton/skeleton_file.h"
#include "util/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace nenrin;
    try {
        Skeleton skeleton = loadSkeletonFile(fuzz::writeInputFile(data, size, ".json"));
        fuzz::probeWood(skeleton, GrainParams{});
    } catch (const InputError&) {
    }
    return 0;
}
