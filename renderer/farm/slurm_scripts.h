#pragma once
/// The SLURM side of a split job or batch (docs/farm.md): an array job whose task K runs one
/// part or frame, and (for split jobs) a merge job that runs when every task succeeded
/// (--dependency=afterok, cancelled if one failed). Written into a job folder on the shared
/// filesystem:
///   tasks.sbatch   the array job; task K retries its command up to `retries` times
///   merge.sbatch   the merge job (split jobs only)
///   submit.sh      submits both, chaining them; records the job ids in *.jobid
///   retry.sh       resubmits only the tasks whose output is missing, and the merge again
///   parts/         the tasks' outputs (split jobs); logs/ one log per task and the merge

#include <string>
#include <vector>

namespace nenrin {

struct SlurmJob {
    std::string name;     ///< job name (letters, digits, '-', '_')
    std::string folder;   ///< absolute path of the job folder
    std::string workdir;  ///< absolute path the tasks run in (relative inputs resolve here)
    std::string nenrin;   ///< absolute path of the nenrin binary on the cluster
    int tasks = 1;        ///< array size: task ids 1..tasks
    /// Task K's arguments to nenrin; "{K}" in an argument becomes the task id.
    std::vector<std::string> taskArgs;
    /// The file each task writes (tasks entries): retry.sh resubmits the tasks without theirs.
    std::vector<std::string> taskOutputs;
    std::vector<std::string> mergeArgs;   ///< empty: no merge job (a batch)
    std::string partition, time, memory;  ///< passed on when set
    int cpusPerTask = 1;
    int retries = 1;  ///< extra attempts of a failed task inside the same allocation
};

/// Shell-quotes one word for bash (single quotes).
std::string shellQuote(const std::string& word);

/// Writes the scripts and creates parts/ and logs/; returns the files written. Throws
/// InputError if the folder cannot be made or written.
std::vector<std::string> writeSlurmJob(const SlurmJob& job);

}  // namespace nenrin
