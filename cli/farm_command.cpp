#include "farm_command.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <memory>

#include "renderer/farm/batch_file.h"
#include "renderer/farm/slurm_scripts.h"
#include "util/atomic_output.h"
#include "util/input_error.h"

namespace nenrin {

namespace {

namespace fs = std::filesystem;

struct FarmOptions {
    int tiles = 0;
    std::string folder;
    std::string name;
    std::string nenrin;
    std::string partition, time, memory;
    int cpusPerTask = 1;
    int retries = 1;
    bool noSubmit = false;
};

/// Takes the value of an option out of `args` ("-o X", "--output X", "--output=X"); "" if absent.
std::string takeOption(std::vector<std::string>& args, std::initializer_list<const char*> names) {
    std::string value;
    for (size_t i = 0; i < args.size();) {
        bool matched = false;
        for (const char* name : names) {
            const std::string n = name;
            if (args[i] == n) {
                if (i + 1 >= args.size())
                    throw InputError("command line", n, "expected a value after it");
                value = args[i + 1];
                args.erase(args.begin() + i, args.begin() + i + 2);
                matched = true;
            } else if (n.size() > 2 && args[i].rfind(n + "=", 0) == 0) {
                value = args[i].substr(n.size() + 1);
                args.erase(args.begin() + i);
                matched = true;
            }
            if (matched) break;
        }
        if (!matched) ++i;
    }
    return value;
}

bool hasOption(const std::vector<std::string>& args, const std::string& name) {
    for (const std::string& a : args)
        if (a == name || a.rfind(name + "=", 0) == 0) return true;
    return false;
}

std::string absolute(const std::string& path) {
    return fs::absolute(path).lexically_normal().string();
}

std::string selfPath() {
    std::error_code ec;
    fs::path p = fs::read_symlink("/proc/self/exe", ec);
    if (ec) throw InputError("nenrin", "", "cannot find its own binary: give --nenrin PATH");
    return p.string();
}

std::string jobName(const std::string& stem) {
    std::string name = "nenrin-";
    for (char c : stem) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '-';
    return name.substr(0, 64);
}

void run(const FarmOptions& o, std::vector<std::string> args) {
    if (args.empty())
        throw InputError("command line", "COMMAND",
                         "missing: render ..., bake slice|volume ... or batch FILE");
    for (const char* banned : {"--tile", "--frame", "--list"})
        if (hasOption(args, banned))
            throw InputError("command line", banned,
                             "the job sets this itself: leave it out of the command");
    SlurmJob job;
    job.workdir = fs::current_path().string();
    job.nenrin = o.nenrin.empty() ? selfPath() : absolute(o.nenrin);
    job.partition = o.partition;
    job.time = o.time;
    job.memory = o.memory;
    job.cpusPerTask = o.cpusPerTask;
    job.retries = o.retries;
    if (!hasOption(args, "-q") && !hasOption(args, "--quiet")) args.push_back("--quiet");
    if (!hasOption(args, "--threads")) {
        args.push_back("--threads");
        args.push_back(std::to_string(o.cpusPerTask));
    }
    std::string stem;
    const std::string& command = args.front();
    if (command == "batch") {
        if (args.size() < 2) throw InputError("command line", "batch", "missing: the batch file");
        if (o.tiles > 0)
            throw InputError("command line", "--tiles",
                             "a batch runs one task per frame: leave --tiles out");
        const std::vector<BatchFrame> frames = loadBatchFile(args[1]);  // checks it now
        job.tasks = static_cast<int>(frames.size());
        for (const BatchFrame& f : frames) job.taskOutputs.push_back(absolute(f.output));
        stem = fs::path(args[1]).stem().string();
        job.folder = absolute(o.folder.empty() ? stem + ".job" : o.folder);
        job.taskArgs = args;
        job.taskArgs.insert(job.taskArgs.end(), {"--frame", "{K}"});
    } else if (command == "render" || command == "bake") {
        if (command == "bake" && (args.size() < 2 || (args[1] != "slice" && args[1] != "volume")))
            throw InputError("command line", "bake",
                             "only bake slice and bake volume split into parts");
        if (o.tiles < 1)
            throw InputError("command line", "--tiles",
                             "missing: the number of parts to split the job into");
        const std::string output = takeOption(args, {"-o", "--output"});
        const std::string png = takeOption(args, {"--png"});
        if (output.empty())
            throw InputError("command line", "-o", "missing: the merged output file");
        stem = fs::path(output).stem().string();
        job.folder = absolute(o.folder.empty() ? stem + ".job" : o.folder);
        job.tasks = o.tiles;
        for (int k = 1; k <= o.tiles; ++k)
            job.taskOutputs.push_back(fmt::format("{}/parts/part-{}.exr", job.folder, k));
        job.taskArgs = args;
        job.taskArgs.insert(job.taskArgs.end(), {"--tile", fmt::format("{{K}}/{}", o.tiles), "-o",
                                                 job.folder + "/parts/part-{K}.exr"});
        job.mergeArgs = {"merge"};
        for (int k = 1; k <= o.tiles; ++k)
            job.mergeArgs.push_back(fmt::format("{}/parts/part-{}.exr", job.folder, k));
        job.mergeArgs.insert(job.mergeArgs.end(), {"-o", absolute(output)});
        if (!png.empty()) job.mergeArgs.insert(job.mergeArgs.end(), {"--png", absolute(png)});
    } else {
        throw InputError(
            "command line", "COMMAND",
            fmt::format("\"{}\": expected render, bake slice, bake volume or batch", command));
    }
    job.name = o.name.empty() ? jobName(stem) : o.name;
    for (const std::string& f : writeSlurmJob(job)) fmt::print("wrote {}\n", f);
    commitOutputs();  // the scripts must be in place before they are submitted
    if (o.noSubmit) {
        fmt::print("not submitted: run {}/submit.sh [sbatch options]\n", job.folder);
        return;
    }
    const std::string submit = shellQuote(job.folder + "/submit.sh");
    std::fflush(stdout);
    const int status = std::system(submit.c_str());
    if (status != 0)
        throw InputError(job.folder + "/submit.sh", "",
                         "submitting failed (is sbatch on PATH and the cluster up?); the scripts "
                         "are in place: run it again when it is");
}

}  // namespace

void addFarmCommand(CLI::App& app) {
    CLI::App* farm = app.add_subcommand("farm", "Run a job on a compute cluster (docs/farm.md)");
    farm->require_subcommand(1);
    auto o = std::make_shared<FarmOptions>();
    CLI::App* slurm = farm->add_subcommand(
        "slurm",
        "Write and submit a SLURM job: a render or bake split into --tiles parts (an array job) "
        "and their merge (a job that runs when all parts succeeded), or one task per frame of a "
        "batch file. The command follows the options, as you would give it to nenrin:\n"
        "  nenrin farm slurm --tiles 16 render scene.json -o out.exr --png out.png --spp 256\n"
        "  nenrin farm slurm --tiles 8 bake volume --skeleton s.json --box ... -o log.vdb\n"
        "  nenrin farm slurm batch catalogue.json\n"
        "The job folder (default: OUTPUT.job) gets tasks.sbatch, merge.sbatch, submit.sh, "
        "retry.sh (resubmits only missing parts), parts/ and logs/. It must be on a filesystem "
        "every node sees; tasks run in the current folder.");
    slurm->prefix_command();
    slurm->add_option("--tiles", o->tiles, "Parts to split a render or bake into (one task each)")
        ->check(CLI::Range(1, 4096));
    slurm->add_option("--job-dir", o->folder, "Job folder (default: OUTPUT.job or BATCH.job)");
    slurm->add_option("--name", o->name, "Job name (default: nenrin-OUTPUT)");
    slurm->add_option("--nenrin", o->nenrin,
                      "The nenrin binary as the nodes see it (default: this one)");
    slurm->add_option("--partition", o->partition, "SLURM partition");
    slurm->add_option("--time", o->time, "Time limit per task, e.g. 02:00:00");
    slurm->add_option("--mem", o->memory, "Memory per node, e.g. 8G");
    slurm
        ->add_option("--cpus-per-task", o->cpusPerTask,
                     "CPUs per task; the command gets --threads this unless it has its own")
        ->check(CLI::Range(1, 1024))
        ->default_val(1);
    slurm->add_option("--retries", o->retries, "Extra attempts of a failed task before it gives up")
        ->check(CLI::Range(0, 10))
        ->default_val(1);
    slurm->add_flag("--no-submit", o->noSubmit, "Write the scripts only");
    slurm->callback([o, slurm] { run(*o, slurm->remaining()); });
}

}  // namespace nenrin
