#include "renderer/jobs/render_job.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <chrono>
#include <map>

#include "renderer/colour_management.h"
#include "renderer/denoise/atrous_denoiser.h"
#include "renderer/film.h"
#include "renderer/scene_file.h"
#include "util/atomic_output.h"
#include "util/input_error.h"
#include "util/limits.h"

namespace nenrin {

namespace {

/// The caller's settings over the scene's.
void applySettings(const RenderJob& job, RenderSettings& s) {
    if (job.width > 0 || job.height > 0) {
        if (!imageSizeAllowed(job.width, job.height))
            throw InputError("command line", "--res",
                             fmt::format("{}x{} is over the {} pixel limit", job.width, job.height,
                                         kMaxImagePixels));
        s.width = job.width;
        s.height = job.height;
    }
    if (job.spp > 0) s.spp = job.spp;
    if (job.noiseThreshold >= 0) s.noiseThreshold = job.noiseThreshold;
    if (job.minSpp >= 0) s.minSpp = job.minSpp;
    if (s.noiseThreshold > 0 && s.minSpp > s.spp)
        throw InputError("command line", "--min-spp",
                         fmt::format("{} is more than the {} samples per pixel allowed (--spp)",
                                     s.minSpp, s.spp));
    if (job.seed >= 0) s.seed = static_cast<uint64_t>(job.seed);
}

/// The EXR header's nenrin:KEY strings; a part also carries the whole job's fingerprint.
std::map<std::string, std::string> renderMetadata(const RenderJob& job, const Scene& scene) {
    const RenderSettings& s = scene.settings;
    std::map<std::string, std::string> metadata{
        {"version", NENRIN_VERSION},
        {"scene", job.scene},
        {"spp", std::to_string(s.spp)},
        {"noise_threshold", fmt::format("{}", s.noiseThreshold)},
        {"seed", std::to_string(s.seed)},
        {"max_depth", std::to_string(s.maxDepth)},
        {"channels", filmChannelDescription(s.noiseThreshold > 0)}};
    if (!job.sets.empty()) metadata["set"] = fmt::format("{}", fmt::join(job.sets, " "));
    if (job.part) {
        // The resolution is in the fingerprint although the frame's size is in every part.
        auto identity = metadata;
        identity["resolution"] = fmt::format("{}x{} min_spp={}", s.width, s.height, s.minSpp);
        labelPart(metadata, JobKind::Render,
                  jobFingerprint(JobKind::Render, identity, scene.source, scene.inputFiles),
                  *job.part);
    }
    return metadata;
}

}  // namespace

RenderJobReport runRenderJob(const RenderJob& job) {
    // Check every output name before the (long) work, so a typo fails at once.
    checkOutputName(job.output, {".exr"});
    if (!job.png.empty()) checkOutputName(job.png, {".png"});
    if (job.part && !job.png.empty())
        throw InputError("command line", "--png",
                         "a part of a split render has no preview: give --png to nenrin merge");
    if (job.part && job.denoise)
        throw InputError("command line", "--denoise",
                         "a part of a split render is not denoised alone (its edges would show): "
                         "merge the parts, then `nenrin denoise MERGED.exr -o OUT.exr`");
    std::unique_ptr<Scene> scene = loadScene(job.scene, parseSceneOverrides(job.sets));
    applySettings(job, scene->settings);
    const RenderSettings& s = scene->settings;

    RenderOptions options;
    options.threads = job.threads;
    options.quiet = job.quiet;
    if (job.part)
        options.rows = bandOfPart(s.height, kRenderTileSize, job.part->part, job.part->parts);
    std::map<std::string, std::string> metadata = renderMetadata(job, *scene);

    RenderJobReport report;
    Film film = renderScene(*scene, options, report.stats);
    if (job.denoise) {
        const auto start = std::chrono::steady_clock::now();
        DenoiseOptions denoise;
        denoise.threads = job.threads;
        denoise.samples = s.spp;
        denoiseFilm(film, denoise);
        report.denoiseSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        metadata["denoised"] = denoiseDescription(denoise);
    }
    writeFilmExr(film, job.output, metadata, job.threads);
    report.written.push_back(job.output);
    if (!job.png.empty()) {
        writePreviewPng(job.png, film.rgb, film.width, film.height);
        report.written.push_back(job.png);
    }
    report.settings = s;
    report.firstRow = film.firstRow;
    report.rows = film.rows;
    report.part = job.part;
    return report;
}

std::string RenderJobReport::summary() const {
    const RenderSettings& s = settings;
    const std::string samples =
        s.noiseThreshold > 0
            ? fmt::format(
                  ", adaptive sampling (noise threshold {}): {:.1f} spp on average, {} at most,",
                  s.noiseThreshold, double(stats.cameraRays) / (double(s.width) * rows), s.spp)
            : fmt::format(" at {} spp", s.spp);
    const std::string size =
        !part ? fmt::format("{}x{}", s.width, s.height)
              : fmt::format("part {}/{} (rows {}..{} of {}x{})", part->part, part->parts, firstRow,
                            firstRow + rows - 1, s.width, s.height);
    const std::string denoised =
        denoiseSeconds >= 0 ? fmt::format("; denoised in {:.2f} s", denoiseSeconds) : "";
    return fmt::format("{}{} in {:.2f} s: {:.2f} M rays/s ({:.2f} M camera rays/s){}", size,
                       samples, stats.seconds, stats.rays / stats.seconds * 1e-6,
                       stats.cameraRays / stats.seconds * 1e-6, denoised);
}

}  // namespace nenrin
