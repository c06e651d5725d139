#pragma once
/// Writes an output file without ever leaving a damaged one behind: the writer fills a
/// temporary file in the same folder (same extension, so format-sniffing writers still work),
/// and commit() renames it over the final name. If commit() is never reached (an error, an
/// exception), the destructor removes the temporary file; one left by a process that was killed
/// while writing is removed by the next AtomicOutput of the same name; after
/// removeOutputsOnSignals(), SIGTERM, SIGINT and SIGHUP remove every temporary file first.

#include <string>
#include <utility>
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

/// All the outputs of a command, committed together. While a transaction is open,
/// AtomicOutput::commit() hands its finished temporary file to it instead of renaming it;
/// commitOutputs() renames every file handed over so far, and a transaction destroyed before
/// that removes them all. So a command that fails after writing some of its outputs (an EXR
/// written, its PNG not) leaves none of them. One transaction at a time (the command's).
class OutputTransaction {
public:
    OutputTransaction();
    ~OutputTransaction();
    OutputTransaction(const OutputTransaction&) = delete;
    OutputTransaction& operator=(const OutputTransaction&) = delete;
};

/// Renames the files handed to the open transaction to their final names (for a command that
/// must publish some outputs before it goes on: a batch after each frame, job scripts before
/// they are submitted). Without a transaction, nothing to do.
void commitOutputs();

/// Call first thing in main, before any thread starts: SIGTERM (timeout, SLURM limits,
/// preemption), SIGINT (Ctrl-C) and SIGHUP then remove every temporary output file in flight
/// (written or handed to the transaction, not yet renamed) and end the process with exit code
/// 128 + the signal. Only SIGKILL still leaves one, for the next run of that output to remove.
void removeOutputsOnSignals();

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
