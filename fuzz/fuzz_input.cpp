#include "fuzz/fuzz_input.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace nenrin::fuzz {

namespace {

struct InputFolder {
    std::string path;
    InputFolder() {
        // tmpfs where there is one: libFuzzer runs thousands of inputs a second.
        std::filesystem::path base = std::filesystem::is_directory("/dev/shm")
                                         ? "/dev/shm"
                                         : std::filesystem::temp_directory_path();
        path = (base / ("nenrin-fuzz-" + std::to_string(getpid()))).string();
        std::filesystem::create_directories(path);
    }
    ~InputFolder() {
        std::error_code ignored;
        std::filesystem::remove_all(path, ignored);
    }
};

}  // namespace

const std::string& inputFolder() {
    static InputFolder folder;
    return folder.path;
}

std::string writeInputFile(const uint8_t* data, size_t size, const std::string& extension) {
    std::string path = inputFolder() + "/input" + extension;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    out.close();
    if (!out) fail("cannot write the fuzz input to " + path);
    return path;
}

void fail(const std::string& what) {
    std::fprintf(stderr, "nenrin fuzz: %s\n", what.c_str());
    std::fflush(stderr);
    std::abort();
}

}  // namespace nenrin::fuzz
