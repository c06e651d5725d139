#include "bake_command.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "arguments.h"
#include "grain/grown_tree.h"
#include "renderer/bake/bake_specs.h"
#include "renderer/bake/grid_bake.h"
#include "renderer/bake/grid_writers.h"
#include "renderer/colour_management.h"
#include "renderer/farm/split_job.h"
#include "skeleton/skeleton_file.h"
#include "util/input_error.h"
#include "uv_bake_command.h"

namespace nenrin {

namespace {

struct CommonOptions {
    std::string skeleton;
    std::string grain;
    std::string output;
    int threads = 0;
    bool quiet = false;
    std::string fellingTime;  ///< years, or "auto"; empty: the grain file's
    std::string tile;         ///< "K/N": bake only part K of N (a split job)
};

void addCommon(CLI::App* cmd, CommonOptions& o) {
    cmd->add_option("--skeleton", o.skeleton, "Skeleton JSON file (docs/skeleton-format.md)")
        ->required();
    cmd->add_option("--grain", o.grain,
                    "Grain parameter JSON file (docs/grain-format.md); defaults if omitted");
    cmd->add_option("-o,--output", o.output, "Output file")->required();
    cmd->add_option("--felling-time", o.fellingTime,
                    "Years: the tree's age when felled (wood with T beyond it is outside the "
                    "log), or 'auto' = the years of the skeleton's ring_widths; overrides the "
                    "grain file's felling_time, 0 = never felled");
    cmd->add_option("--threads", o.threads, "Worker threads (0 = all cores)")
        ->check(CLI::Range(0, 1024))
        ->default_val(0);
    cmd->add_flag("-q,--quiet", o.quiet, "No progress bar");
    addMaxMemoryOption(cmd);
    cmd->add_option("--tile", o.tile,
                    "K/N: bake only part K of N (a band of whole bake tiles) into an EXR part "
                    "file, for a cluster; `nenrin merge` puts the parts together, byte-identical "
                    "to one bake (docs/farm.md)");
}

/// A split job's part: the grid keeps only its band of layers and is labelled with the job's
/// fingerprint. Parts are always EXR, and have no preview.
void makePart(BakedGrid& grid, const CommonOptions& o, JobKind kind, const std::string& png) {
    if (o.tile.empty()) return;
    const PartNumber number = parsePartNumber(o.tile, "command line", "--tile");
    if (lowerExtension(o.output) != ".exr")
        throw InputError(o.output, "", "a part of a split bake (--tile) is written as .exr");
    if (!png.empty())
        throw InputError("command line", "--png",
                         "a part of a split bake has no preview: give --png to nenrin merge");
    const RowBand band =
        bandOfPart(grid.layerCount(), bakeTileLayers(grid.isVolume()), number.part, number.parts);
    grid.layerBegin = band.begin;
    grid.layerEnd = band.end;
    std::vector<std::string> inputs{o.skeleton};
    if (!o.grain.empty()) inputs.push_back(o.grain);
    const std::string fingerprint = jobFingerprint(kind, grid.metadata, "", inputs);
    labelPart(grid.metadata, kind, fingerprint, number);
}

/// Everything a bake needs, loaded and validated before any output is touched.
struct LoadedWood {
    std::unique_ptr<GrownTree> tree;
    std::unique_ptr<WoodShader> shader;
};

std::unique_ptr<LoadedWood> loadWood(const CommonOptions& o) {
    Skeleton skeleton = loadSkeletonFile(o.skeleton);
    GrainParams grain = o.grain.empty() ? GrainParams{} : loadGrainFile(o.grain);
    if (o.fellingTime == "auto") {
        if (skeleton.ringWidths().empty())
            throw InputError("command line", "--felling-time",
                             "'auto' needs a skeleton with ring_widths (its recorded years); "
                             "give the age in years instead");
        grain.fellingTime = static_cast<double>(skeleton.ringWidths().size());
    } else if (!o.fellingTime.empty()) {
        char* end = nullptr;
        double t = std::strtod(o.fellingTime.c_str(), &end);
        if (*end != '\0' || !std::isfinite(t) || t < 0)
            throw InputError("command line", "--felling-time",
                             fmt::format("\"{}\": expected years >= 0 or 'auto'", o.fellingTime));
        grain.fellingTime = t;
    }
    auto w = std::make_unique<LoadedWood>();
    w->tree = std::make_unique<GrownTree>(std::move(skeleton), std::move(grain));
    w->shader = std::make_unique<WoodShader>(w->tree->field());
    return w;
}

void addMetadata(BakedGrid& grid, const CommonOptions& o, const LoadedWood& w) {
    grid.metadata["version"] = NENRIN_VERSION;
    grid.metadata["skeleton"] = o.skeleton;
    grid.metadata["grain"] = grainToJson(w.tree->grain()).dump();
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

/// Wall-clock seconds of a bake's three stages: the sampling rate counts only the middle one
/// (loading a big skeleton file can take longer than sampling it).
struct BakeTimes {
    double setUp = 0;  ///< reading the skeleton and grain, building the index and field
    double baking = 0;
    double writing = 0;
};

void report(const BakedGrid& grid, const std::vector<std::string>& files, const BakeTimes& t) {
    // Statistics of the wood only: samples outside a felled log (A = 0) do not count.
    float tMin = INFINITY, tMax = -INFINITY, knotMax = 0;
    size_t wood = 0;
    for (size_t i = 0; i < grid.sampleCount(); ++i) {
        const float* px = &grid.data[i * BakedGrid::kChannels];
        if (px[3] <= 0) continue;
        ++wood;
        tMin = std::min(tMin, px[4]);
        tMax = std::max(tMax, px[4]);
        knotMax = std::max(knotMax, px[5]);
    }
    for (const auto& f : files) fmt::print("wrote {}\n", f);
    fmt::print("{} samples in {:.2f} s ({:.2f} M samples/s; set-up {:.2f} s, writing {:.2f} s); ",
               grid.sampleCount(), t.baking, grid.sampleCount() / std::max(t.baking, 1e-9) * 1e-6,
               t.setUp, t.writing);
    if (wood == 0) {
        fmt::print("no wood: every sample is outside the felled log\n");
        return;
    }
    fmt::print("wood {:.1f}%, T {:.2f}..{:.2f} years, knot max {:.2f}\n",
               100.0 * wood / grid.sampleCount(), tMin, tMax, knotMax);
}

double since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

void addBakeCommands(CLI::App& app) {
    CLI::App* bake =
        app.add_subcommand("bake", "Bake the wood of a skeleton into images or volumes");
    bake->require_subcommand(1);

    // --- slice ---
    static CommonOptions sliceCommon;
    static std::string plane = "cross", size = "0.4x0.4m", res = "512x512";
    static double at = 1.0, bottom = 0.0;
    CLI::App* slice = bake->add_subcommand(
        "slice",
        "A planar cut through the log as an EXR image (R,G,B,A,T,knot).\n"
        "  cross:      horizontal cut at height --at, centred on the pith (an end-grain cookie)\n"
        "  radial:     vertical cut through plane y = pith + --at (quarter-sawn near 0)\n"
        "  tangential: vertical cut through plane x = pith + --at (a flat-sawn board face)\n"
        "Boards span --size WIDTHxHEIGHT with the lower edge at --bottom.");
    addCommon(slice, sliceCommon);
    slice->add_option("--plane", plane, "cross | radial | tangential")
        ->check(CLI::IsMember({"cross", "radial", "tangential"}))
        ->default_val("cross");
    slice->add_option("--at", at, "Height of a cross cut, or board offset from the pith (m)")
        ->default_val(1.0);
    slice->add_option("--size", size, "Image extent WIDTHxHEIGHT in metres, e.g. 0.4x0.4m")
        ->default_val("0.4x0.4m");
    slice->add_option("--res", res, "Image resolution WIDTHxHEIGHT in pixels")
        ->default_val("512x512");
    slice->add_option("--bottom", bottom, "Boards: height of the image's lower edge (m)")
        ->default_val(0.0);
    static std::string slicePng;
    slice->add_option("--png", slicePng,
                      "Also write an 8-bit sRGB preview of the colour through OpenColorIO");
    slice->callback([] {
        auto t0 = std::chrono::steady_clock::now();
        SliceSpec spec;
        spec.plane = parseSlicePlane(plane);
        for (auto [value, option] : {std::pair{at, "--at"}, std::pair{bottom, "--bottom"}})
            if (!std::isfinite(value) || std::abs(value) > kMaxCoordinate)
                throw InputError("command line", option,
                                 fmt::format("expected a finite number of metres in [-{:g}, {:g}], "
                                             "found {:g}",
                                             kMaxCoordinate, kMaxCoordinate, value));
        spec.at = at;
        spec.bottom = bottom;
        std::tie(spec.width, spec.height) = parseSizeMetres(size, "--size");
        std::tie(spec.resX, spec.resY) = parseResolution(res, "--res", kMaxImageSide);
        if (!imageSizeAllowed(spec.resX, spec.resY))
            throw InputError(
                "command line", "--res",
                fmt::format("{} is over the cap of {} M pixels", res, kMaxImagePixels >> 20));
        checkOutputName(sliceCommon.output, {".exr"});
        if (!slicePng.empty()) checkOutputName(slicePng, {".png"});
        auto wood = loadWood(sliceCommon);
        BakedGrid grid = sliceGrid(wood->tree->skeleton(), spec);
        addMetadata(grid, sliceCommon, *wood);
        grid.metadata["slice"] =
            fmt::format("plane={} at={} size={}x{}m bottom={}", slicePlaneName(spec.plane), spec.at,
                        spec.width, spec.height, spec.bottom);
        makePart(grid, sliceCommon, JobKind::BakeSlice, slicePng);
        BakeTimes times;
        times.setUp = since(t0);
        const auto tBake = std::chrono::steady_clock::now();
        bakeGrid(*wood->shader, grid, {sliceCommon.threads, sliceCommon.quiet, "Baking slice"});
        times.baking = since(tBake);
        const auto tWrite = std::chrono::steady_clock::now();
        auto files = writeExr(grid, sliceCommon.output);
        if (!slicePng.empty()) {
            writeSlicePreviewPng(grid, slicePng);
            files.push_back(slicePng);
        }
        times.writing = since(tWrite);
        report(grid, files, times);
    });

    // --- volume ---
    static CommonOptions volumeCommon;
    static std::string box;
    static int volumeRes = 64;
    CLI::App* volume = bake->add_subcommand(
        "volume",
        "A 3D grid of the wood over a box, as EXR (z-slice atlas), OpenVDB (one grid per\n"
        "channel) or POV-Ray df3 (16-bit R, G, B, knot files plus a .inc pigment).\n"
        "Samples sit on the box's lattice, faces included.");
    addCommon(volume, volumeCommon);
    volume->add_option("--box", box, "Tree-space box x0,y0,z0,x1,y1,z1 in metres")->required();
    volume->add_option("--res", volumeRes, "Samples along the box's longest edge (2..512)")
        ->default_val(64);
    volume->callback([] {
        auto t0 = std::chrono::steady_clock::now();
        auto b = parseNumberList(box, "--box", 6);
        VolumeSpec spec;
        spec.lower = {b[0], b[1], b[2]};
        spec.upper = {b[3], b[4], b[5]};
        for (double v : b)
            if (std::abs(v) > kMaxCoordinate)
                throw InputError("command line", "--box",
                                 fmt::format("{:g} m is beyond the +-{:g} m nenrin works in", v,
                                             kMaxCoordinate));
        for (int i = 0; i < 3; ++i)
            if (!(spec.upper[i] > spec.lower[i]))
                throw InputError("command line", "--box",
                                 fmt::format("zero-size or inverted box: expected x1 > x0, y1 > "
                                             "y0 and z1 > z0, found \"{}\"",
                                             box));
        if (volumeRes < 2 || volumeRes > kMaxVolumeSide)
            throw InputError(
                "command line", "--res",
                fmt::format("expected 2 to {} samples, found {}", kMaxVolumeSide, volumeRes));
        spec.resolution = volumeRes;
        checkOutputName(volumeCommon.output, {".exr", ".vdb", ".df3"});
        auto wood = loadWood(volumeCommon);
        BakedGrid grid = volumeGrid(spec);
        addMetadata(grid, volumeCommon, *wood);
        grid.metadata["box"] = box;
        makePart(grid, volumeCommon, JobKind::BakeVolume, "");
        BakeTimes times;
        times.setUp = since(t0);
        const auto tBake = std::chrono::steady_clock::now();
        bakeGrid(*wood->shader, grid, {volumeCommon.threads, volumeCommon.quiet, "Baking volume"});
        times.baking = since(tBake);
        const auto tWrite = std::chrono::steady_clock::now();
        auto files = writeVolume(grid, volumeCommon.output);
        times.writing = since(tWrite);
        report(grid, files, times);
    });

    addUvBakeCommand(bake);
}

}  // namespace nenrin
