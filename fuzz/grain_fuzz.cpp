// Grain parameter files (docs/grain-format.md): read, then a small tree shaded with them.
#include "fuzz/fuzz_input.h"
#include "fuzz/wood_probe.h"
#include "grain/grain_params.h"
#include "util/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace nenrin;
    static const Skeleton tree = fuzz::probeTree();
    try {
        GrainParams params = loadGrainFile(fuzz::writeInputFile(data, size, ".json"));
        fuzz::probeWood(tree, params);
    } catch (const InputError&) {
    }
    return 0;
}
