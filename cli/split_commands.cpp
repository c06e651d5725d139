#include "split_commands.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <chrono>
#include <filesystem>
#include <memory>

#include "arguments.h"
#include "render_command.h"
#include "renderer/farm/batch_file.h"
#include "renderer/farm/part_merge.h"
#include "util/atomic_output.h"
#include "util/input_error.h"

namespace nenrin {

void addMergeCommand(CLI::App& app) {
    struct Options {
        std::vector<std::string> parts;
        std::string output, png;
    };
    auto o = std::make_shared<Options>();
    CLI::App* cmd = app.add_subcommand(
        "merge",
        "Put the parts of a split render or bake (--tile K/N) together. The parts must be of the "
        "same job (same fingerprint) and cover the frame exactly once; the result is "
        "byte-identical to the one-machine job. On any problem (a missing, doubled, damaged or "
        "foreign part) nothing is written.");
    cmd->add_option("parts", o->parts, "The part files (EXR), in any order")->required();
    cmd->add_option("-o,--output", o->output,
                    "Output: .exr (render, slice, volume), .vdb or .df3 (volume)")
        ->required();
    cmd->add_option("--png", o->png, "Also write an 8-bit sRGB preview (render, slice)");
    addMaxMemoryOption(cmd);
    cmd->callback([o] {
        auto t0 = std::chrono::steady_clock::now();
        checkMergeOutputs(o->output, o->png);
        MergedJob job = mergeParts(o->parts);
        for (const std::string& f : writeMergedJob(job, o->output, o->png))
            fmt::print("wrote {}\n", f);
        fmt::print("merged {} parts of a {} of {}x{} in {:.2f} s\n", job.parts,
                   jobKindName(job.kind), job.image.width, job.image.height,
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    });
}

void addBatchCommand(CLI::App& app) {
    struct Options {
        std::string file;
        int frame = 0;
        bool list = false;
        int threads = 0;
        bool quiet = false;
    };
    auto o = std::make_shared<Options>();
    CLI::App* cmd = app.add_subcommand(
        "batch",
        "Render the frames of a batch file (a scene list and/or a parameter sweep, "
        "docs/farm.md): all of them one after the other, or one (--frame I, as a cluster task "
        "does). Frame I is byte-identical to `nenrin render SCENE --set ...` with its "
        "overrides.");
    cmd->add_option("file", o->file, "Batch JSON file")->required();
    cmd->add_option("--frame", o->frame, "Render only frame I (1-based, see --list)")
        ->check(CLI::Range(1, 1000000));
    cmd->add_flag("--list", o->list,
                  "List the frames (number, name, output, overrides); render nothing");
    cmd->add_option("--threads", o->threads, "Worker threads (0 = all cores)")
        ->check(CLI::Range(0, 1024))
        ->default_val(0);
    cmd->add_flag("-q,--quiet", o->quiet, "No progress bar");
    addMaxMemoryOption(cmd);
    cmd->callback([o] {
        const std::vector<BatchFrame> frames = loadBatchFile(o->file);
        if (o->list) {
            for (size_t i = 0; i < frames.size(); ++i)
                fmt::print("{}\t{}\t{}\t{}\n", i + 1, frames[i].name, frames[i].output,
                           fmt::join(frames[i].sets, " "));
            return;
        }
        if (o->frame > static_cast<int>(frames.size()))
            throw InputError(
                "command line", "--frame",
                fmt::format("frame {}: {} has {} frames", o->frame, o->file, frames.size()));
        const size_t first = o->frame > 0 ? o->frame - 1 : 0;
        const size_t last = o->frame > 0 ? o->frame : frames.size();
        for (size_t i = first; i < last; ++i) {
            const BatchFrame& f = frames[i];
            fmt::print("frame {}/{}: {}\n", i + 1, frames.size(), f.name);
            std::error_code ec;
            std::filesystem::create_directories(std::filesystem::path(f.output).parent_path(),
                                                ec);  // render names a failure
            RenderJob job;
            job.scene = f.scene;
            job.output = f.output;
            job.png = f.png;
            job.sets = f.sets;
            job.threads = o->threads;
            job.quiet = o->quiet;
            runRenderPrinting(job);
            commitOutputs();  // a later frame's failure must not take this one with it
        }
    });
}

}  // namespace nenrin
