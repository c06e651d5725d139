#include "render_command.h"

#include <fmt/format.h>

#include <string>

#include "arguments.h"
#include "renderer/colour_management.h"

namespace nenrin {

namespace {

/// The options as typed: --res and --tile are parsed into the job.
struct RenderArguments {
    RenderJob job;
    std::string resolution, tile;
};

}  // namespace

void runRenderPrinting(const RenderJob& job) {
    const RenderJobReport report = runRenderJob(job);
    for (const std::string& file : report.written)
        if (file == job.png)
            fmt::print("wrote {} ({})\n", file, displayConfigName());
        else
            fmt::print("wrote {}\n", file);
    fmt::print("{}\n", report.summary());
}

void addRenderCommand(CLI::App& app) {
    auto arguments = std::make_shared<RenderArguments>();
    RenderJob* o = &arguments->job;
    CLI::App* cmd = app.add_subcommand(
        "render", "Path-trace a scene (docs/scene-format.md) to an EXR with AOVs");
    cmd->add_option("scene", o->scene, "Scene JSON file")->required();
    cmd->add_option("-o,--output", o->output, "Output EXR (R,G,B,A + AOVs)")->required();
    cmd->add_option("--spp", o->spp,
                    "Samples per pixel (overrides the scene); with --noise-threshold, the most a "
                    "pixel takes")
        ->check(CLI::Range(1, kMaxSpp));
    cmd->add_option(
           "--noise-threshold", o->noiseThreshold,
           "Adaptive sampling: a pixel stops when the estimated standard error of its mean over "
           "the square root of its mean (summed over R,G,B) is at most this, for it and "
           "its neighbours (e.g. 0.01; 0 = off, every pixel takes --spp; overrides the "
           "scene)")
        ->check(finiteRange(0.0, 1.0));
    cmd->add_option("--min-spp", o->minSpp,
                    "Adaptive sampling: samples every pixel takes before its noise is estimated "
                    "(0 = min(spp, 16); overrides the scene)")
        ->check(CLI::Range(0, kMaxSpp));
    cmd->add_option("--res", arguments->resolution,
                    "Resolution WxH (overrides the scene), e.g. 640x400");
    cmd->add_option("--threads", o->threads, "Worker threads (0 = all cores)")
        ->check(CLI::Range(0, 1024))
        ->default_val(0);
    cmd->add_option("--seed", o->seed, "Random seed (overrides the scene)")
        ->check(CLI::Range(0LL, 1LL << 53));
    cmd->add_option("--png", o->png, "Also write an 8-bit sRGB preview through OpenColorIO");
    cmd->add_flag("-q,--quiet", o->quiet, "No progress bar");
    cmd->add_flag(
        "--denoise", o->denoise,
        "Denoise the image before it is written: the edge-avoiding a-trous filter "
        "guided by the albedo, normal, depth, visibility, occlusion and variance AOVs, diffuse "
        "light and gloss apart (docs/denoise.md)");
    addMaxMemoryOption(cmd);
    cmd->add_option("--tile", arguments->tile,
                    "K/N: render only part K of N (a band of whole 16-pixel tile rows) into a "
                    "part EXR, for a cluster; `nenrin merge` puts the parts together, "
                    "byte-identical to one render (docs/farm.md)");
    cmd->add_option("--set", o->sets,
                    "POINTER=VALUE: set a value of the scene JSON before it is read, e.g. "
                    "/render/seed=7, '/camera/position=[1,2,3]', /materials/0/species=sugi "
                    "(repeatable; VALUE is JSON, or else a string)");
    cmd->callback([arguments] {
        RenderJob job = arguments->job;
        if (!arguments->resolution.empty())
            std::tie(job.width, job.height) =
                parseResolution(arguments->resolution, "--res", kMaxImageSide);
        if (!arguments->tile.empty())
            job.part = parsePartNumber(arguments->tile, "command line", "--tile");
        runRenderPrinting(job);
    });
}

}  // namespace nenrin
