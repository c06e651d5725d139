#include "renderer/farm/slurm_scripts.h"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>

#include "util/atomic_output.h"
#include "util/input_error.h"

namespace nenrin {

namespace {

namespace fs = std::filesystem;

/// `args` as a bash command line, "{K}" replaced by "$k".
std::string commandLine(const std::string& nenrin, const std::vector<std::string>& args) {
    std::string line = shellQuote(nenrin);
    for (const std::string& a : args) {
        std::string quoted = shellQuote(a);
        for (size_t at; (at = quoted.find("{K}")) != std::string::npos;)
            quoted.replace(at, 3, "'\"$k\"'");
        line += " " + quoted;
    }
    return line;
}

std::string header(const SlurmJob& job, const std::string& name, const std::string& log) {
    std::string h = "#!/bin/bash\n";
    h += fmt::format("#SBATCH --job-name={}\n", name);
    h += fmt::format("#SBATCH --chdir={}\n", job.workdir);
    h += fmt::format("#SBATCH --output={}/logs/{}\n", job.folder, log);
    h += fmt::format("#SBATCH --cpus-per-task={}\n", job.cpusPerTask);
    if (!job.partition.empty()) h += fmt::format("#SBATCH --partition={}\n", job.partition);
    if (!job.time.empty()) h += fmt::format("#SBATCH --time={}\n", job.time);
    if (!job.memory.empty()) h += fmt::format("#SBATCH --mem={}\n", job.memory);
    return h;
}

}  // namespace

std::string shellQuote(const std::string& word) {
    std::string q = "'";
    for (char c : word) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

std::vector<std::string> writeSlurmJob(const SlurmJob& job) {
    std::error_code ec;
    for (const char* sub : {"parts", "logs"}) {
        fs::create_directories(fs::path(job.folder) / sub, ec);
        if (ec)
            throw InputError(job.folder, "",
                             fmt::format("cannot make the job folder: {}", ec.message()));
    }
    const bool merge = !job.mergeArgs.empty();
    std::vector<std::string> files;
    auto write = [&](const std::string& name, const std::string& text) {
        const std::string path = (fs::path(job.folder) / name).string();
        AtomicOutput out(path);
        std::ofstream f(out.temporaryPath(), std::ios::binary);
        f << text;
        f.close();
        if (!f) throw InputError(path, "", "cannot write the job script (disk full?)");
        fs::permissions(out.temporaryPath(),
                        fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                        fs::perm_options::add, ec);
        out.commit();
        files.push_back(path);
    };

    std::string tasks = header(job, job.name, "task-%a.log");
    tasks += fmt::format("#SBATCH --array=1-{}\n", job.tasks);
    tasks += fmt::format(
        "# nenrin: task K of {} runs `nenrin {}` for its part or frame, and tries again up to "
        "{} time(s) if it fails.\n",
        job.tasks, job.taskArgs.empty() ? "" : job.taskArgs.front(), job.retries);
    tasks += "set -u\n";
    tasks += "k=${SLURM_ARRAY_TASK_ID:?not run as a SLURM array task}\n";
    tasks += fmt::format("for attempt in $(seq 1 {}); do\n", job.retries + 1);
    tasks += "    echo \"nenrin task $k, attempt $attempt on $(hostname) at $(date -Is)\"\n";
    tasks += "    if " + commandLine(job.nenrin, job.taskArgs) + "; then exit 0; fi\n";
    tasks += "    echo \"nenrin task $k: attempt $attempt failed\" >&2\n";
    tasks += "done\nexit 1\n";
    write("tasks.sbatch", tasks);

    if (merge) {
        std::string m = header(job, job.name + "-merge", "merge.log");
        m += "# nenrin: runs when every task succeeded (submit.sh chains it with afterok).\n";
        m += "exec " + commandLine(job.nenrin, job.mergeArgs) + "\n";
        write("merge.sbatch", m);
    }

    // submit.sh [sbatch options for both jobs, e.g. --partition=...]
    std::string submit = "#!/bin/bash\n# Submits the nenrin job in this folder: the array of tasks";
    submit += merge ? ", then the merge once all succeeded.\n" : ".\n";
    submit += "set -euo pipefail\ncd \"$(dirname \"$0\")\"\n";
    submit += "tasks=$(sbatch --parsable \"$@\" tasks.sbatch)\ntasks=${tasks%%;*}\n";
    submit += "echo \"$tasks\" > tasks.jobid\n";
    if (merge) {
        submit +=
            "merge=$(sbatch --parsable \"$@\" --dependency=afterok:\"$tasks\" "
            "--kill-on-invalid-dep=yes merge.sbatch)\nmerge=${merge%%;*}\n";
        submit += "echo \"$merge\" > merge.jobid\n";
        submit += "echo \"nenrin: submitted tasks $tasks and merge $merge\"\n";
    } else {
        submit += "echo \"nenrin: submitted tasks $tasks\"\n";
    }
    write("submit.sh", submit);

    // retry.sh: only the tasks whose output is missing (outputs are written atomically, so a
    // file that exists is complete), then the merge again.
    std::string retry = "#!/bin/bash\n# Resubmits the tasks whose output is missing";
    retry += merge ? ", and the merge.\n" : ".\n";
    retry += "set -euo pipefail\ncd \"$(dirname \"$0\")\"\noutputs=(\n";
    for (const std::string& output : job.taskOutputs) retry += "    " + shellQuote(output) + "\n";
    retry += ")\nmissing=()\n";
    retry += fmt::format("for k in $(seq 1 {}); do\n", job.tasks);
    retry += "    [[ -e \"${outputs[k-1]}\" ]] || missing+=(\"$k\")\ndone\n";
    retry += "if ((${#missing[@]} == 0)); then\n";
    retry += merge ? "    echo \"nenrin: every task's output is there; submitting the merge\"\n"
                     "    merge=$(sbatch --parsable \"$@\" merge.sbatch)\n"
                     "    echo \"${merge%%;*}\" > merge.jobid\n    exit 0\nfi\n"
                   : "    echo \"nenrin: every task's output is there\"\n    exit 0\nfi\n";
    retry += "list=$(IFS=,; echo \"${missing[*]}\")\n";
    retry +=
        "tasks=$(sbatch --parsable \"$@\" --array=\"$list\" tasks.sbatch)\n"
        "tasks=${tasks%%;*}\necho \"$tasks\" > tasks.jobid\n";
    if (merge) {
        retry +=
            "merge=$(sbatch --parsable \"$@\" --dependency=afterok:\"$tasks\" "
            "--kill-on-invalid-dep=yes merge.sbatch)\nmerge=${merge%%;*}\n"
            "echo \"$merge\" > merge.jobid\n";
        retry += "echo \"nenrin: resubmitted tasks $list as $tasks, merge $merge\"\n";
    } else {
        retry += "echo \"nenrin: resubmitted tasks $list as $tasks\"\n";
    }
    write("retry.sh", retry);
    return files;
}

}  // namespace nenrin
