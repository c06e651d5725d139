#include "util/module_loader.h"

#include <dlfcn.h>
#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>
#include <vector>

#include "util/input_error.h"

namespace nenrin {

void* moduleSymbol(const std::string& fileName, const std::string& builtPath, const char* symbol,
                   const std::string& feature) {
    static std::mutex mutex;
    static std::map<std::string, void*> handles;
    std::lock_guard<std::mutex> lock(mutex);
    void*& handle = handles[fileName];
    std::string tried;
    if (!handle) {
        std::vector<std::string> candidates;
        if (const char* dir = std::getenv("NENRIN_MODULE_DIR"))
            candidates.push_back((std::filesystem::path(dir) / fileName).string());
        candidates.push_back(builtPath);
        std::error_code ec;
        auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
        if (!ec) candidates.push_back((self.parent_path() / fileName).string());
        for (const std::string& c : candidates) {
            handle = dlopen(c.c_str(), RTLD_NOW | RTLD_LOCAL);
            if (handle) break;
            tried += fmt::format("{}{}: {}", tried.empty() ? "" : "; ", c, dlerror());
        }
    }
    void* address = handle ? dlsym(handle, symbol) : nullptr;
    if (!address)
        throw InputError(
            feature, "",
            fmt::format("cannot load the module {} ({}{})", fileName,
                        handle ? "no symbol " : "tried ", handle ? std::string(symbol) : tried));
    return address;
}

}  // namespace nenrin
