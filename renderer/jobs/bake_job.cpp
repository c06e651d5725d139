#include "renderer/jobs/bake_job.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "grain/grown_tree.h"
#include "renderer/bake/grid_bake.h"
#include "renderer/bake/grid_writers.h"
#include "skeleton/skeleton_file.h"
#include "util/input_error.h"

namespace nenrin {

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Everything a bake needs, loaded and validated before any output is touched.
struct LoadedWood {
    std::unique_ptr<GrownTree> tree;
    std::unique_ptr<WoodShader> shader;
};

LoadedWood loadWood(const BakeJob& job) {
    Skeleton skeleton = loadSkeletonFile(job.skeleton);
    GrainParams grain = job.grain.empty() ? GrainParams{} : loadGrainFile(job.grain);
    if (job.fellingTime == "auto") {
        if (skeleton.ringWidths().empty())
            throw InputError("command line", "--felling-time",
                             "'auto' needs a skeleton with ring_widths (its recorded years); "
                             "give the age in years instead");
        grain.fellingTime = static_cast<double>(skeleton.ringWidths().size());
    } else if (!job.fellingTime.empty()) {
        char* end = nullptr;
        double t = std::strtod(job.fellingTime.c_str(), &end);
        if (*end != '\0' || !std::isfinite(t) || t < 0)
            throw InputError("command line", "--felling-time",
                             fmt::format("\"{}\": expected years >= 0 or 'auto'", job.fellingTime));
        grain.fellingTime = t;
    }
    Finish finish;
    if (!finishPreset(job.finish, finish))
        throw InputError(
            "command line", "--finish",
            fmt::format("expected one of {}, found \"{}\"", finishPresetNames(), job.finish));
    LoadedWood w;
    w.tree = std::make_unique<GrownTree>(std::move(skeleton), std::move(grain));
    w.shader = std::make_unique<WoodShader>(w.tree->field(), finish);
    return w;
}

void addMetadata(BakedGrid& grid, const BakeJob& job, const GrownTree& tree) {
    grid.metadata["version"] = NENRIN_VERSION;
    grid.metadata["skeleton"] = job.skeleton;
    grid.metadata["grain"] = grainToJson(tree.grain()).dump();
    grid.metadata["finish"] = job.finish;
    grid.metadata["channels"] =
        "R,G,B: scene-linear albedo; A: coverage (0 outside the felled log); T: growth time "
        "(years); knot: branch share (0..1)";
    // Where each sample sits in tree space: sample (i, j, k) = origin + i x + j y + k z, so
    // a pixel can be traced back to the wood without re-deriving the pith position.
    auto vec = [](const Vec3& v) { return fmt::format("{} {} {}", v.x, v.y, v.z); };
    grid.metadata["sample_origin"] = vec(grid.origin);
    grid.metadata["sample_step_x"] = vec(grid.stepX);
    grid.metadata["sample_step_y"] = vec(grid.stepY);
    grid.metadata["sample_step_z"] = vec(grid.stepZ);
}

/// A split job's part: the grid keeps only its band of layers and is labelled with the job's
/// fingerprint. Parts are always EXR, and have no preview.
void makePart(BakedGrid& grid, const BakeJob& job, JobKind kind) {
    if (!job.part) return;
    if (lowerExtension(job.output) != ".exr")
        throw InputError(job.output, "", "a part of a split bake (--tile) is written as .exr");
    if (!job.png.empty())
        throw InputError("command line", "--png",
                         "a part of a split bake has no preview: give --png to nenrin merge");
    const RowBand band = bandOfPart(grid.layerCount(), bakeTileLayers(grid.isVolume()),
                                    job.part->part, job.part->parts);
    grid.layerBegin = band.begin;
    grid.layerEnd = band.end;
    std::vector<std::string> inputs{job.skeleton};
    if (!job.grain.empty()) inputs.push_back(job.grain);
    const std::string fingerprint = jobFingerprint(kind, grid.metadata, "", inputs);
    labelPart(grid.metadata, kind, fingerprint, *job.part);
}

/// Statistics of the wood only: samples outside a felled log (A = 0) do not count.
void measure(const BakedGrid& grid, BakeReport& report) {
    report.samples = grid.sampleCount();
    float tMin = INFINITY, tMax = -INFINITY, knotMax = 0;
    for (size_t i = 0; i < grid.sampleCount(); ++i) {
        const float* px = &grid.data[i * BakedGrid::kChannels];
        if (px[3] <= 0) continue;
        ++report.woodSamples;
        tMin = std::min(tMin, px[4]);
        tMax = std::max(tMax, px[4]);
        knotMax = std::max(knotMax, px[5]);
    }
    if (report.woodSamples > 0) report.tMin = tMin, report.tMax = tMax, report.knotMax = knotMax;
}

/// Bakes a grid set up by `setUp` and writes it with `write`, timing each stage.
template <typename SetUp, typename Write>
BakeReport bake(const BakeJob& job, JobKind kind, const char* title, SetUp setUp, Write write) {
    const auto t0 = Clock::now();
    const LoadedWood wood = loadWood(job);
    BakedGrid grid = setUp(*wood.tree);
    addMetadata(grid, job, *wood.tree);
    makePart(grid, job, kind);
    BakeReport report;
    report.setUpSeconds = since(t0);
    const auto tBake = Clock::now();
    bakeGrid(*wood.shader, grid, {job.threads, job.quiet, title});
    report.bakeSeconds = since(tBake);
    const auto tWrite = Clock::now();
    report.written = write(grid);
    report.writeSeconds = since(tWrite);
    measure(grid, report);
    return report;
}

}  // namespace

BakeReport runSliceBake(const BakeJob& job, const SliceSpec& spec) {
    checkOutputName(job.output, {".exr"});
    if (!job.png.empty()) checkOutputName(job.png, {".png"});
    auto setUp = [&](const GrownTree& tree) {
        BakedGrid grid = sliceGrid(tree.skeleton(), spec);
        auto vec = [](const Vec3& v) { return fmt::format("{},{},{}", v.x, v.y, v.z); };
        grid.metadata["slice"] =
            spec.cut
                ? fmt::format("origin={} right={} up={}", vec(spec.cut->origin),
                              vec(spec.cut->right), vec(spec.cut->up))
                : fmt::format("plane={} at={} size={}x{}m bottom={}", slicePlaneName(spec.plane),
                              spec.at, spec.width, spec.height, spec.bottom);
        return grid;
    };
    auto write = [&](const BakedGrid& grid) {
        std::vector<std::string> files = writeExr(grid, job.output);
        if (!job.png.empty()) {
            writeSlicePreviewPng(grid, job.png);
            files.push_back(job.png);
        }
        return files;
    };
    return bake(job, JobKind::BakeSlice, "Baking slice", setUp, write);
}

BakeReport runVolumeBake(const BakeJob& job, const VolumeSpec& spec, const std::string& box) {
    checkOutputName(job.output, {".exr", ".vdb", ".df3"});
    auto setUp = [&](const GrownTree&) {
        BakedGrid grid = volumeGrid(spec);
        grid.metadata["box"] = box;
        return grid;
    };
    auto write = [&](const BakedGrid& grid) { return writeVolume(grid, job.output); };
    return bake(job, JobKind::BakeVolume, "Baking volume", setUp, write);
}

std::string BakeReport::summary() const {
    std::string line = fmt::format(
        "{} samples in {:.2f} s ({:.2f} M samples/s; set-up {:.2f} s, writing {:.2f} "
        "s); ",
        samples, bakeSeconds, samples / std::max(bakeSeconds, 1e-9) * 1e-6, setUpSeconds,
        writeSeconds);
    if (woodSamples == 0) return line + "no wood: every sample is outside the felled log";
    return line + fmt::format("wood {:.1f}%, T {:.2f}..{:.2f} years, knot max {:.2f}",
                              100.0 * woodSamples / samples, tMin, tMax, knotMax);
}

}  // namespace nenrin
