#include "util/atomic_output.h"

#include <fmt/format.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <system_error>
#include <thread>

#include "util/input_error.h"

namespace nenrin {

namespace fs = std::filesystem;

namespace {

/// Every temporary file that may exist now: registered before it is created, released once it
/// is renamed or removed. What a caught signal removes.
struct InFlight {
    std::mutex mutex;
    std::set<std::string> paths;
};
InFlight& inFlight() {
    static InFlight* f = new InFlight;  // never destroyed: the signal thread may outlive main
    return *f;
}
void track(const std::string& path) {
    std::lock_guard<std::mutex> lock(inFlight().mutex);
    inFlight().paths.insert(path);
}
void untrack(const std::string& path) {
    std::lock_guard<std::mutex> lock(inFlight().mutex);
    inFlight().paths.erase(path);
}

constexpr int kCleanUpSignals[] = {SIGTERM, SIGINT, SIGHUP};

}  // namespace

void removeOutputsOnSignals() {
    sigset_t set;
    sigemptyset(&set);
    for (int s : kCleanUpSignals) sigaddset(&set, s);
    // Blocked here, so in every thread started later: only the waiting thread takes them.
    if (pthread_sigmask(SIG_BLOCK, &set, nullptr) != 0) return;
    std::thread([set] {
        int sig = 0;
        if (sigwait(&set, &sig) != 0) return;
        // The lock is never released: no thread registers a new file after this.
        inFlight().mutex.lock();
        for (const std::string& path : inFlight().paths) ::unlink(path.c_str());
        _exit(128 + sig);
    }).detach();
}

void checkOutputPath(const std::string& path) {
    if (path.empty()) throw InputError("command line", "output", "the output file name is empty");
    fs::path p(path);
    fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw InputError(path, "",
                         "cannot write output: folder '" + dir.string() + "' does not exist");
    if (fs::is_directory(p, ec))
        throw InputError(path, "", "cannot write output: this is a folder, expected a file name");
    // An output replaces its target by a rename: only ever a regular file (never a device, a
    // FIFO or a socket, and not the target of a symbolic link, which would be replaced by a file).
    const fs::file_status target = fs::symlink_status(p, ec);
    if (!ec && fs::exists(target) && !fs::is_regular_file(target))
        throw InputError(path, "",
                         fmt::format("cannot write output: it exists and is {}, not a regular file",
                                     fs::is_symlink(target)          ? "a symbolic link"
                                     : fs::is_fifo(target)           ? "a FIFO"
                                     : fs::is_socket(target)         ? "a socket"
                                     : fs::is_block_file(target)     ? "a block device"
                                     : fs::is_character_file(target) ? "a character device"
                                                                     : "not a regular file"));
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
    if (path.empty())
        throw InputError("command line", "output",
                         "the output file name is empty: expected a name ending in " + list);
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

/// Removes the temporary files of this output left by processes that died while writing it
/// (killed, power lost): `.STEM.partial-PID.EXT` whose PID is no longer running.
void removeStalePartials(const fs::path& dir, const fs::path& final) {
    const std::string prefix = "." + final.stem().string() + ".partial-";
    const std::string extension = final.extension().string();
    std::error_code ec;
    for (auto it = fs::directory_iterator(dir, ec); !ec && it != fs::directory_iterator();
         it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.rfind(prefix, 0) != 0 || name.size() < prefix.size() + extension.size() ||
            name.compare(name.size() - extension.size(), extension.size(), extension) != 0)
            continue;
        const std::string digits =
            name.substr(prefix.size(), name.size() - prefix.size() - extension.size());
        if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos ||
            digits.size() > 9)
            continue;
        const pid_t pid = static_cast<pid_t>(std::stol(digits));
        if (pid != getpid() && kill(pid, 0) != 0 && errno == ESRCH) {
            std::error_code removeError;
            fs::remove(it->path(), removeError);
        }
    }
}

AtomicOutput::AtomicOutput(std::string path) : final_(std::move(path)) {
    checkOutputPath(final_);
    fs::path p(final_);
    fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    removeStalePartials(dir, p);
    std::string name = ".";
    name += p.stem().string();
    name += ".partial-";
    name += std::to_string(getpid());
    name += p.extension().string();
    temporary_ = (dir / name).string();
    track(temporary_);
}

AtomicOutput::~AtomicOutput() {
    if (!committed_) {
        std::error_code ec;
        fs::remove(temporary_, ec);
        untrack(temporary_);
    }
}

namespace {

/// The open transaction's files: (temporary, final) in the order they were finished.
struct Pending {
    bool open = false;
    std::vector<std::pair<std::string, std::string>> files;
};
Pending& pending() {
    static Pending p;
    return p;
}
std::mutex& pendingMutex() {
    static std::mutex m;
    return m;
}

void rename(const std::string& temporary, const std::string& final) {
    std::error_code ec;
    fs::rename(temporary, final, ec);
    if (ec) throw InputError(final, "", "cannot write output: " + ec.message());
}

}  // namespace

OutputTransaction::OutputTransaction() {
    std::lock_guard<std::mutex> lock(pendingMutex());
    pending().open = true;
    pending().files.clear();
}

OutputTransaction::~OutputTransaction() {
    std::lock_guard<std::mutex> lock(pendingMutex());
    std::error_code ec;
    for (const auto& [temporary, final] : pending().files) {
        fs::remove(temporary, ec);
        untrack(temporary);
    }
    pending() = {};
}

void commitOutputs() {
    std::lock_guard<std::mutex> lock(pendingMutex());
    auto& files = pending().files;
    // Renamed in order; should one fail (the folder vanished), the rest stay temporary and
    // are removed with the transaction.
    while (!files.empty()) {
        rename(files.front().first, files.front().second);
        untrack(files.front().first);
        files.erase(files.begin());
    }
}

void AtomicOutput::commit() {
    {
        std::lock_guard<std::mutex> lock(pendingMutex());
        if (pending().open) {
            pending().files.emplace_back(temporary_, final_);
            committed_ = true;  // the transaction owns the temporary file now
            return;
        }
    }
    rename(temporary_, final_);
    untrack(temporary_);
    committed_ = true;
}

}  // namespace nenrin
