#pragma once
/// Writes an output file without ever leaving a damaged one behind: the writer fills a
/// temporary file in the same folder (same extension, so format-sniffing writers still work),
/// and commit() renames it over the final name. If commit() is never reached (an error, an
/// exception), the destructor removes the temporary file.

#include <string>
#include <vector>

namespace nenrin {

/// Throws InputError unless `path` names a file that could be created: its folder exists and
/// is writable, and it is not itself a folder. Call before long work.
void checkOutputPath(const std::string& path);

/// Throws InputError unless `path` ends in one of `extensions` (lower case, with the dot) and
/// can be written (its folder exists and is writable). Call before baking, so a bad name
/// fails at once rather than after the work.
void checkOutputName(const std::string& path, const std::vector<std::string>& extensions);

/// The extension of `path` in lower case, with its dot ("" when it has none).
std::string lowerExtension(const std::string& path);

/// Writes `text` to `path` through an AtomicOutput: all of it, or nothing (the old file, if
/// any, stays). Throws InputError "cannot write the <what> (disk full?)" when the writing fails.
void writeTextAtomically(const std::string& path, const std::string& text, const std::string& what);

class AtomicOutput {
public:
    /// Checks that the folder of `path` exists and is writable; throws InputError otherwise.
    explicit AtomicOutput(std::string path);
    ~AtomicOutput();
    AtomicOutput(const AtomicOutput&) = delete;
    AtomicOutput& operator=(const AtomicOutput&) = delete;

    /// Where the writer should write now.
    const std::string& temporaryPath() const { return temporary_; }
    const std::string& finalPath() const { return final_; }
    /// Moves the finished temporary file to its final name.
    void commit();

private:
    std::string final_;
    std::string temporary_;
    bool committed_ = false;
};

}  // namespace nenrin
