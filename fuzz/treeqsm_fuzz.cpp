// TreeQSM cylinder lists, text and CSV (docs/trees.md): imported, then grown and shaded.
#include "fuzz/fuzz_input.h"
#include "fuzz/wood_probe.h"
#include "skeleton/sources/measured/qsm_import.h"
#include "util/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace nenrin;
    try {
        QsmTree tree = importQsm(fuzz::writeInputFile(data, size, ".txt"));
        GrainParams params;
        params.radialSpeed = tree.ringWidth;
        fuzz::probeWood(tree.skeleton, params);
    } catch (const InputError&) {
    }
    return 0;
}
