#pragma once
// The fixture of the end-to-end tests of the nenrin command: each test runs the binary
// (NENRIN_BINARY) in its own fresh temporary directory with absolute paths, and checks that a
// bad input ends in one error line, a non-zero exit and no output left behind.

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kBinary = NENRIN_BINARY;
const fs::path kSourceDir = NENRIN_SOURCE_DIR;

inline fs::path skeletonScene(const std::string& name) {
    return kSourceDir / "scenes" / "skeletons" / name;
}
inline fs::path grainScene(const std::string& name) {
    return kSourceDir / "scenes" / "grain" / name;
}
inline fs::path badFixture(const std::string& name) {
    return kSourceDir / "tests" / "data" / "bad" / name;
}

inline std::string shellQuote(const std::string& s) {
    std::string q = "'";
    for (char c : s) {
        if (c == '\'')
            q += "'\\''";
        else
            q += c;
    }
    return q + "'";
}

inline std::string readText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

inline std::vector<unsigned char> readBytes(const fs::path& path) {
    std::string s = readText(path);
    return {s.begin(), s.end()};
}

/// Counts the non-overlapping occurrences of `needle` in `haystack`.
inline size_t countOf(const std::string& haystack, const std::string& needle) {
    size_t n = 0;
    for (size_t p = haystack.find(needle); p != std::string::npos;
         p = haystack.find(needle, p + needle.size()))
        ++n;
    return n;
}

struct RunResult {
    int exitCode = -1;  ///< the exit status, or 128 + signal if the process was killed
    std::string out;
    std::string err;
};

/// Options of a bake, by name; kOmit drops a default.
using Options = std::map<std::string, std::string>;
const std::string kOmit = "\x01omit";

struct Image {
    OIIO::ImageSpec spec;
    std::string format;
    std::vector<float> pixels;  ///< all channels, interleaved, as float
};

/// Reads a whole image as float; nullopt (and a test failure) if it cannot be read.
inline std::optional<Image> readImage(const fs::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) {
        ADD_FAILURE() << "cannot open " << path << ": " << OIIO::geterror();
        return std::nullopt;
    }
    Image img;
    img.spec = in->spec();
    img.format = in->format_name();
    img.pixels.resize(size_t(img.spec.width) * img.spec.height * img.spec.depth *
                      img.spec.nchannels);
    if (!in->read_image(0, 0, 0, img.spec.nchannels, OIIO::TypeDesc::FLOAT, img.pixels.data())) {
        ADD_FAILURE() << "cannot read " << path << ": " << in->geterror();
        return std::nullopt;
    }
    in->close();
    return img;
}

inline int channelIndex(const OIIO::ImageSpec& spec, const std::string& name) {
    for (size_t c = 0; c < spec.channelnames.size(); ++c)
        if (spec.channelnames[c] == name) return static_cast<int>(c);
    return -1;
}

class CliTest : public ::testing::Test {
protected:
    void SetUp() override {
        std::string pattern = (fs::temp_directory_path() / "nenrin-cli-XXXXXX").string();
        std::vector<char> buffer(pattern.begin(), pattern.end());
        buffer.push_back('\0');
        ASSERT_NE(mkdtemp(buffer.data()), nullptr) << "mkdtemp: " << std::strerror(errno);
        root_ = buffer.data();
        out_ = root_ / "out";
        in_ = root_ / "in";
        fs::create_directory(out_);
        fs::create_directory(in_);
        ASSERT_TRUE(fs::exists(kBinary)) << "no nenrin binary at " << kBinary;
    }

    void TearDown() override {
        if (root_.empty()) return;
        std::error_code ec;
        // A test may have made a folder read-only; give it back so it can be removed.
        for (auto it = fs::recursive_directory_iterator(root_, ec);
             !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
            if (it->is_directory(ec)) fs::permissions(it->path(), fs::perms::owner_all, ec);
        fs::permissions(root_, fs::perms::owner_all, ec);
        fs::remove_all(root_, ec);
    }

    /// Runs nenrin with `args` from inside the (otherwise empty) output folder, so that a stray
    /// relative file would also show up in outputFiles().
    RunResult run(const std::vector<std::string>& args) {
        const fs::path outFile = root_ / "stdout.txt", errFile = root_ / "stderr.txt";
        std::string cmd = fmt::format("cd {} && exec {}", shellQuote(out_.string()),
                                      shellQuote(kBinary.string()));
        for (const auto& a : args) cmd += fmt::format(" {}", shellQuote(a));
        cmd += fmt::format(" </dev/null >{} 2>{}", shellQuote(outFile.string()),
                           shellQuote(errFile.string()));
        int status = std::system(cmd.c_str());
        RunResult r;
        if (status != -1 && WIFEXITED(status))
            r.exitCode = WEXITSTATUS(status);
        else if (status != -1 && WIFSIGNALED(status))
            r.exitCode = 128 + WTERMSIG(status);
        r.out = readText(outFile);
        r.err = readText(errFile);
        return r;
    }

    static std::vector<std::string> bakeArgs(const std::string& kind, Options options,
                                             const Options& overrides) {
        for (const auto& [key, value] : overrides) options[key] = value;
        std::vector<std::string> args{"bake", kind, "-q"};
        for (const auto& [key, value] : options) {
            if (value == kOmit) continue;
            args.push_back(key);
            args.push_back(value);
        }
        return args;
    }

    /// A tiny cross-section bake of the straight trunk into out/slice.exr, with overrides.
    RunResult slice(const Options& overrides = {}) {
        return run(bakeArgs("slice",
                            {{"--skeleton", skeletonScene("straight-trunk.json").string()},
                             {"--plane", "cross"},
                             {"--at", "1"},
                             {"--size", "0.4x0.4m"},
                             {"--res", "32x32"},
                             {"-o", (out_ / "slice.exr").string()}},
                            overrides));
    }

    /// A tiny volume bake of the straight trunk into out/volume.exr, with overrides.
    RunResult volume(const Options& overrides = {}) {
        return run(bakeArgs("volume",
                            {{"--skeleton", skeletonScene("straight-trunk.json").string()},
                             {"--box", "-0.1,-0.1,0.9,0.1,0.1,1.1"},
                             {"--res", "8"},
                             {"-o", (out_ / "volume.exr").string()}},
                            overrides));
    }

    /// Every file and folder under the output folder (hidden ones included), relative to it.
    std::vector<std::string> outputFiles() const {
        std::vector<std::string> files;
        std::error_code ec;
        for (auto it = fs::recursive_directory_iterator(out_, ec);
             !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
            files.push_back(fs::relative(it->path(), out_).string());
        std::sort(files.begin(), files.end());
        return files;
    }

    std::string fixture(const std::string& name) {
        fs::path p = badFixture(name);
        EXPECT_TRUE(fs::exists(p)) << "missing fixture " << p;
        return p.string();
    }

    /// A failed run: non-zero exit, every `expected` piece in stderr, nothing in the output folder.
    void expectFailure(const RunResult& r, const std::vector<std::string>& expected) {
        EXPECT_NE(r.exitCode, 0) << "stdout:\n" << r.out << "stderr:\n" << r.err;
        EXPECT_LT(r.exitCode, 128) << "killed by a signal; stderr:\n" << r.err;
        for (const auto& piece : expected)
            EXPECT_NE(r.err.find(piece), std::string::npos) << "stderr lacks \"" << piece << "\":\n"
                                                            << r.err;
        EXPECT_EQ(outputFiles(), std::vector<std::string>{}) << "output left behind";
    }

    /// A bad input reported by nenrin itself: exit 1 and exactly one line
    /// `nenrin: error: FILE: PLACE: message`.
    void expectInputError(const RunResult& r, const std::vector<std::string>& expected) {
        expectFailure(r, expected);
        EXPECT_EQ(r.exitCode, 1);
        EXPECT_EQ(r.err.rfind("nenrin: error: ", 0), 0u) << r.err;
        EXPECT_EQ(countOf(r.err, "\n"), 1u) << "expected one line:\n" << r.err;
        EXPECT_TRUE(!r.err.empty() && r.err.back() == '\n') << r.err;
    }

    fs::path root_, out_, in_;
};

}  // namespace
