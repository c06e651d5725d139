#pragma once
/// The files a texture-set writer puts into one folder, each written under a temporary name
/// (util/atomic_output.h) and renamed only by commit(), when all are complete.

#include <memory>
#include <string>
#include <vector>

#include "util/atomic_output.h"

namespace nenrin {

class FolderOutputs {
public:
    /// Throws InputError naming `folder` unless it is an existing folder; `what` says what the
    /// folder was for ("the maps").
    FolderOutputs(std::string folder, const std::string& what);

    /// Starts the file `name` in the folder; returns the temporary path to write to.
    const std::string& add(const std::string& name);
    /// The final path of the file added last (for error messages).
    const std::string& last() const { return files_.back(); }
    /// Renames every file to its final name; returns the final paths.
    std::vector<std::string> commit();

private:
    std::string folder_;
    std::vector<std::unique_ptr<AtomicOutput>> outputs_;
    std::vector<std::string> files_;
};

}  // namespace nenrin
