#include "util/atomic_output.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "util/input_error.h"

namespace nenrin {

namespace fs = std::filesystem;

void checkOutputPath(const std::string& path) {
    if (path.empty()) throw InputError("", "output", "empty output path");
    fs::path p(path);
    fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw InputError(path, "",
                         "cannot write output: folder '" + dir.string() + "' does not exist");
    if (fs::is_directory(p, ec))
        throw InputError(path, "", "cannot write output: this is a folder, expected a file name");
    if (access(dir.c_str(), W_OK) != 0)
        throw InputError(path, "",
                         "cannot write output: folder '" + dir.string() + "' is not writable");
}

std::string lowerExtension(const std::string& path) {
    std::string e = fs::path(path).extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
    return e;
}

void checkOutputName(const std::string& path, const std::vector<std::string>& extensions) {
    std::string e = lowerExtension(path);
    std::string list;
    bool known = false;
    for (const auto& x : extensions) {
        known |= e == x;
        list += (list.empty() ? "" : ", ") + x;
    }
    if (!known)
        throw InputError(path, "",
                         "unsupported output file name: expected a name ending in " + list);
    checkOutputPath(path);
}

void writeTextAtomically(const std::string& path, const std::string& text,
                         const std::string& what) {
    AtomicOutput out(path);
    {
        std::ofstream f(out.temporaryPath(), std::ios::binary);
        f << text;
        f.close();
        if (!f) throw InputError(path, "", "cannot write the " + what + " (disk full?)");
    }
    out.commit();
}

AtomicOutput::AtomicOutput(std::string path) : final_(std::move(path)) {
    checkOutputPath(final_);
    fs::path p(final_);
    fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    std::string name = ".";
    name += p.stem().string();
    name += ".partial-";
    name += std::to_string(getpid());
    name += p.extension().string();
    temporary_ = (dir / name).string();
}

AtomicOutput::~AtomicOutput() {
    if (!committed_) {
        std::error_code ec;
        fs::remove(temporary_, ec);
    }
}

void AtomicOutput::commit() {
    std::error_code ec;
    fs::rename(temporary_, final_, ec);
    if (ec) throw InputError(final_, "", "cannot write output: " + ec.message());
    committed_ = true;
}

}  // namespace nenrin
