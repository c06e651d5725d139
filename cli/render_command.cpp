#include "render_command.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <string>

#include "arguments.h"
#include "renderer/colour_management.h"
#include "renderer/farm/split_job.h"
#include "renderer/path_tracer.h"
#include "renderer/scene_file.h"
#include "util/atomic_output.h"
#include "util/input_error.h"

namespace nenrin {

SceneOverrides parseSceneOverrides(const std::vector<std::string>& sets) {
    SceneOverrides overrides;
    for (const std::string& set : sets) {
        const size_t eq = set.find('=');
        if (eq == std::string::npos || eq == 0 || set[0] != '/')
            throw InputError("command line", "--set",
                             fmt::format("\"{}\": expected /json/pointer=VALUE, e.g. "
                                         "/render/seed=7 or '/camera/position=[1,2,3]'",
                                         set));
        nlohmann::json value;
        try {
            value = nlohmann::json::parse(set.substr(eq + 1));
        } catch (const nlohmann::json::exception&) {
            value = set.substr(eq + 1);  // a bare word is a string: /materials/0/species=sugi
        }
        overrides.values.emplace_back(set.substr(0, eq), std::move(value));
    }
    return overrides;
}

void runRender(const RenderJob& o) {
    // Check every output name before the (long) work, so a typo fails at once.
    checkOutputName(o.output, {".exr"});
    if (!o.png.empty()) checkOutputName(o.png, {".png"});
    PartNumber part;
    if (!o.tile.empty()) {
        part = parsePartNumber(o.tile, "command line", "--tile");
        if (!o.png.empty())
            throw InputError("command line", "--png",
                             "a part of a split render has no preview: give --png to nenrin "
                             "merge");
    }
    std::unique_ptr<Scene> scene = loadScene(o.scene, parseSceneOverrides(o.sets));
    RenderSettings& s = scene->settings;
    if (!o.resolution.empty()) {
        auto [w, h] = parseResolution(o.resolution, "--res", kMaxImageSide);
        if (!imageSizeAllowed(w, h))
            throw InputError(
                "command line", "--res",
                fmt::format("{}x{} is over the {} pixel limit", w, h, kMaxImagePixels));
        s.width = w;
        s.height = h;
    }
    if (o.spp > 0) s.spp = o.spp;
    if (o.noiseThreshold >= 0) s.noiseThreshold = o.noiseThreshold;
    if (o.minSpp >= 0) s.minSpp = o.minSpp;
    if (s.noiseThreshold > 0 && s.minSpp > s.spp)
        throw InputError("command line", "--min-spp",
                         fmt::format("{} is more than the {} samples per pixel allowed (--spp)",
                                     s.minSpp, s.spp));
    if (o.seed >= 0) s.seed = static_cast<uint64_t>(o.seed);

    RenderOptions options;
    options.threads = o.threads;
    options.quiet = o.quiet;
    if (!o.tile.empty())
        options.rows = bandOfPart(s.height, kRenderTileSize, part.part, part.parts);

    std::map<std::string, std::string> metadata{
        {"version", NENRIN_VERSION},
        {"scene", o.scene},
        {"spp", std::to_string(s.spp)},
        {"noise_threshold", fmt::format("{}", s.noiseThreshold)},
        {"seed", std::to_string(s.seed)},
        {"max_depth", std::to_string(s.maxDepth)},
        {"channels",
         "R,G,B: scene-linear radiance; A: coverage; albedo; N: world normal; Z: depth along "
         "the view axis (m); T: growth time (years); knot: 0..1; lamella: board id or -1"}};
    if (!o.sets.empty()) metadata["set"] = fmt::format("{}", fmt::join(o.sets, " "));
    if (!o.tile.empty()) {
        // The resolution is in the fingerprint although the frame's size is in every part.
        auto identity = metadata;
        identity["resolution"] = fmt::format("{}x{} min_spp={}", s.width, s.height, s.minSpp);
        labelPart(metadata, JobKind::Render,
                  jobFingerprint(JobKind::Render, identity, scene->source, scene->inputFiles),
                  part);
    }
    RenderStats stats;
    Film film = renderScene(*scene, options, stats);
    writeFilmExr(film, o.output, metadata);
    fmt::print("wrote {}\n", o.output);
    if (!o.png.empty()) {
        writePreviewPng(o.png, film.rgb, film.width, film.height);
        fmt::print("wrote {} ({})\n", o.png, displayConfigName());
    }
    const std::string samples =
        s.noiseThreshold > 0
            ? fmt::format(
                  ", adaptive sampling (noise threshold {}): {:.1f} spp on average, {} at most,",
                  s.noiseThreshold, double(stats.cameraRays) / (double(film.width) * film.rows),
                  s.spp)
            : fmt::format(" at {} spp", s.spp);
    const std::string size =
        o.tile.empty()
            ? fmt::format("{}x{}", s.width, s.height)
            : fmt::format("part {}/{} (rows {}..{} of {}x{})", part.part, part.parts, film.firstRow,
                          film.firstRow + film.rows - 1, s.width, s.height);
    fmt::print("{}{} in {:.2f} s: {:.2f} M rays/s ({:.2f} M camera rays/s)\n", size, samples,
               stats.seconds, stats.rays / stats.seconds * 1e-6,
               stats.cameraRays / stats.seconds * 1e-6);
}

void addRenderCommand(CLI::App& app) {
    auto o = std::make_shared<RenderJob>();
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
    cmd->add_option("--res", o->resolution, "Resolution WxH (overrides the scene), e.g. 640x400");
    cmd->add_option("--threads", o->threads, "Worker threads (0 = all cores)")
        ->check(CLI::Range(0, 1024))
        ->default_val(0);
    cmd->add_option("--seed", o->seed, "Random seed (overrides the scene)")
        ->check(CLI::Range(0LL, 1LL << 53));
    cmd->add_option("--png", o->png, "Also write an 8-bit sRGB preview through OpenColorIO");
    cmd->add_flag("-q,--quiet", o->quiet, "No progress bar");
    addMaxMemoryOption(cmd);
    cmd->add_option("--tile", o->tile,
                    "K/N: render only part K of N (a band of whole 16-pixel tile rows) into a "
                    "part EXR, for a cluster; `nenrin merge` puts the parts together, "
                    "byte-identical to one render (docs/farm.md)");
    cmd->add_option("--set", o->sets,
                    "POINTER=VALUE: set a value of the scene JSON before it is read, e.g. "
                    "/render/seed=7, '/camera/position=[1,2,3]', /materials/0/species=sugi "
                    "(repeatable; VALUE is JSON, or else a string)");
    cmd->callback([o] { runRender(*o); });
}

}  // namespace nenrin
