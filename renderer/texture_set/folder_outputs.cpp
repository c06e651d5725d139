#include "renderer/texture_set/folder_outputs.h"

#include <filesystem>

#include "util/input_error.h"

namespace nenrin {

FolderOutputs::FolderOutputs(std::string folder, const std::string& what)
    : folder_(std::move(folder)) {
    if (!std::filesystem::is_directory(folder_))
        throw InputError(folder_, "output", "expected an existing folder for " + what);
}

const std::string& FolderOutputs::add(const std::string& name) {
    files_.push_back((std::filesystem::path(folder_) / name).string());
    outputs_.push_back(std::make_unique<AtomicOutput>(files_.back()));
    return outputs_.back()->temporaryPath();
}

std::vector<std::string> FolderOutputs::commit() {
    for (auto& o : outputs_) o->commit();
    return files_;
}

}  // namespace nenrin
