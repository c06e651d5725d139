// JSON text (util/json_parse.h): simdjson's document, where it gives one, must be the one
// nlohmann's strict parse gives, and that parse must not refuse it.
#include <string>

#include "fuzz/fuzz_input.h"
#include "util/input_error.h"
#include "util/json_parse.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace nenrin;
    const std::string text(reinterpret_cast<const char*>(data), size);
    std::optional<nlohmann::json> fast = parseJsonFast(text);
    if (!fast) return 0;
    try {
        const std::string difference = jsonDifference(*fast, parseJsonReportingErrors(text, "f"));
        if (!difference.empty()) fuzz::fail("the two parsers disagree: " + difference);
    } catch (const InputError& e) {
        fuzz::fail(std::string("simdjson took what the strict parse refuses: ") + e.what());
    }
    return 0;
}
