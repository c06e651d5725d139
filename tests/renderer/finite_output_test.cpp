#include "renderer/finite_output.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "renderer/exr_file.h"
#include "tests/scratch_path.h"

namespace nenrin {
namespace {

// The writers' last guard: a NaN or Inf never reaches a file, and the error says where it was.
TEST(FiniteOutput, ANonFiniteSampleIsNamedAndNothingIsWritten) {
    const auto path = scratchPath("finite-output.exr");
    std::filesystem::remove(path);
    std::vector<float> pixels(2 * 2 * 3, 0.5f);
    pixels[4] = std::nanf("");  // sample (1, 0), G
    try {
        writeFloatExr(path.string(), path.string(), 2, 2, {"R", "G", "B"}, pixels.data(), {});
        ADD_FAILURE() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("sample (1, 0), channel G is nan"), std::string::npos)
            << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(path));
    pixels[4] = 0.5f;
    pixels[11] = -INFINITY;  // sample (1, 1) of a band starting at row 8
    EXPECT_THROW(
        try {
            requireFiniteOutput(pixels.data(), pixels.size(), {"R", "G", "B"}, 2, 8, "x.exr");
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find("x.exr: sample (1, 9), channel B is -inf"),
                      std::string::npos)
                << e.what();
            throw;
        },
        std::runtime_error);
}

}  // namespace
}  // namespace nenrin
