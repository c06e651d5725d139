// Stand files (docs/stand-kunii.md): read, then the dominant tree felled and shaded.
#include "fuzz/fuzz_input.h"
#include "fuzz/wood_probe.h"
#include "skeleton/sources/kunii/kunii_fell.h"
#include "skeleton/sources/kunii/kunii_stand_file.h"
#include "util/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace nenrin;
    try {
        Stand stand = loadStandFile(fuzz::writeInputFile(data, size, ".json"));
        Skeleton tree = fellStandTree(stand, pickStandTree(stand, TreePick::Dominant));
        fuzz::probeWood(tree, GrainParams{});
    } catch (const InputError&) {
    }
    return 0;
}
