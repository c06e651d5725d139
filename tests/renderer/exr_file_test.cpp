// renderer/exr_file: an EXR written with its blocks compressed on several threads is the same
// file, byte for byte, as one written on one thread, and reads back as written.

#include "renderer/exr_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "util/hash.h"

namespace nenrin {
namespace {

std::string fileBytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(ExrFile, ThreadsCompressTheSameBytes) {
    // 300 rows: 19 blocks of 16, the last one short; values that compress a little.
    const int width = 97, height = 300;
    std::vector<float> pixels(size_t(width) * height * 2);
    for (size_t i = 0; i < pixels.size(); ++i)
        pixels[i] = float(i % 7 == 0 ? uniform01(3, i) : double(i % 300) / 300);
    const auto dir = std::filesystem::temp_directory_path();
    std::vector<std::string> files;
    for (int threads : {1, 2, 4}) {
        const auto path = dir / ("nenrin-exr-threads-" + std::to_string(threads) + ".exr");
        writeFloatExr(path.string(), path.string(), width, height, {"R", "Z"}, pixels.data(),
                      {{"k", "v"}}, {}, ExrValues::SceneLinear, threads);
        files.push_back(fileBytes(path));
        if (threads == 4) {
            const FloatExr back = readFloatExr(path.string());
            ASSERT_EQ(back.pixels.size(), pixels.size());
            EXPECT_EQ(back.pixels, pixels);
        }
        std::filesystem::remove(path);
    }
    ASSERT_GT(files[0].size(), 1000u);
    EXPECT_EQ(files[1], files[0]);
    EXPECT_EQ(files[2], files[0]);
}

}  // namespace
}  // namespace nenrin
