// Tucson .rwl ring series (docs/ring-series.md): read, every series' widths checked, and the
// first series taken as the latewood of itself (the earlywood/latewood pairing).
#include <cmath>

#include "fuzz/fuzz_input.h"
#include "skeleton/ring_series.h"
#include "util/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace nenrin;
    try {
        RingSeriesFile file = readTucsonRwl(fuzz::writeInputFile(data, size, ".rwl"));
        for (const RingSeries& s : file.series)
            for (double w : s.widthsMm)
                if (!std::isfinite(w) || w < 0)
                    fuzz::fail("a ring width that is not finite and >= 0");
        if (!file.series.empty()) {
            for (double share : latewoodShares(file.series[0], file))
                if (!std::isfinite(share)) fuzz::fail("a non-finite latewood share");
            totalFromEarlyLate(file.series[0], file);
        }
    } catch (const InputError&) {
    }
    return 0;
}
