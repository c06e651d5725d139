// Measured-branch files (docs/trees.md): read, then the tree grown and shaded.
#include "fuzz/fuzz_input.h"
#include "fuzz/wood_probe.h"
#include "skeleton/sources/measured/measured_branches.h"
#include "util/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace nenrin;
    try {
        Skeleton tree = loadMeasuredBranches(fuzz::writeInputFile(data, size, ".json"));
        fuzz::probeWood(tree, GrainParams{});
    } catch (const InputError&) {
    }
    return 0;
}
