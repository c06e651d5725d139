#pragma once
/// Where a test writes its files: the system's temporary folder, under a name that carries the
/// process id, so that test runs on one machine at once (ctest's parallel jobs, two clones'
/// suites) never share a file.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace nenrin {

/// A file or folder name in the temporary folder, unique to this process.
inline std::filesystem::path scratchPath(const std::string& name) {
    return std::filesystem::temp_directory_path() /
           ("nenrin-" + std::to_string(getpid()) + "-" + name);
}

/// A fresh, empty folder at scratchPath(name) for one test, removed when it goes out of scope
/// unless the test has failed by then (then it is kept to look at) or NENRIN_KEEP_SCRATCH is
/// set (to hold a passing run's files beside a failing one's: the fit's synthetic cubes).
class ScratchFolder {
public:
    explicit ScratchFolder(const std::string& name) : path_(scratchPath(name)) {
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~ScratchFolder() {
        std::error_code ignored;
        if (!::testing::Test::HasFailure() && !std::getenv("NENRIN_KEEP_SCRATCH"))
            std::filesystem::remove_all(path_, ignored);
    }
    ScratchFolder(const ScratchFolder&) = delete;
    ScratchFolder& operator=(const ScratchFolder&) = delete;

    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

}  // namespace nenrin
