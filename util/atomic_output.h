#pragma once
/// Writes an output file without ever leaving a damaged one behind: the writer fills a
/// temporary file in the same folder (same extension, so format-sniffing writers still work),
/// and commit() renames it over the final name. If commit() is never reached (an error, an
/// exception), the destructor removes the temporary file.

#include <string>

namespace nenrin {

/// Throws InputError unless `path` names a file that could be created: its folder exists and
/// is writable, and it is not itself a folder. Call before long work.
void checkOutputPath(const std::string& path);

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
