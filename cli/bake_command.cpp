#include "bake_command.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "arguments.h"
#include "renderer/jobs/bake_job.h"
#include "util/input_error.h"
#include "util/vec3.h"
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

/// The job the common options describe (--tile parsed).
BakeJob bakeJob(const CommonOptions& o, const std::string& png) {
    BakeJob job;
    job.skeleton = o.skeleton;
    job.grain = o.grain;
    job.output = o.output;
    job.png = png;
    job.fellingTime = o.fellingTime;
    job.threads = o.threads;
    job.quiet = o.quiet;
    if (!o.tile.empty()) job.part = parsePartNumber(o.tile, "command line", "--tile");
    return job;
}

void print(const BakeReport& report) {
    for (const std::string& f : report.written) fmt::print("wrote {}\n", f);
    fmt::print("{}\n", report.summary());
}

struct SliceOptions {
    CommonOptions common;
    std::string plane = "cross", size = "0.4x0.4m", res = "512x512", png, finish = "oiled";
    double at = 1.0, bottom = 0.0;
    std::string origin, right, up;  ///< a cut through any plane (all three, or none)
};

/// --origin, --right and --up as a PlaneCut: three finite points or vectors within the metres
/// nenrin works in, the edges neither zero nor parallel.
PlaneCut parsePlaneCut(const SliceOptions& o) {
    auto vector = [](const std::string& text, const char* option) {
        if (text.empty())
            throw InputError("command line", option,
                             "a cut through any plane needs all of --origin, --right and --up");
        const std::vector<double> v = parseNumberList(text, option, 3);
        for (double x : v)
            if (std::abs(x) > kMaxCoordinate)
                throw InputError("command line", option,
                                 fmt::format("{:g} m is beyond the +-{:g} m nenrin works in", x,
                                             kMaxCoordinate));
        return Vec3{v[0], v[1], v[2]};
    };
    PlaneCut cut{vector(o.origin, "--origin"), vector(o.right, "--right"), vector(o.up, "--up")};
    if (length(cut.right) < 1e-9)
        throw InputError("command line", "--right", "the image's bottom edge has no length");
    if (length(cut.up) < 1e-9)
        throw InputError("command line", "--up", "the image's left edge has no length");
    if (length(cross(normalize(cut.right), normalize(cut.up))) < 1e-6)
        throw InputError("command line", "--up",
                         "parallel to --right: expected the two edges of a plane");
    return cut;
}

struct VolumeOptions {
    CommonOptions common;
    std::string box;
    int res = 64;
};

void addSliceCommand(CLI::App* bake) {
    auto o = std::make_shared<SliceOptions>();
    CLI::App* slice = bake->add_subcommand(
        "slice",
        "A planar cut through the log as an EXR image (R,G,B,A,T,knot).\n"
        "  cross:      horizontal cut at height --at, centred on the pith (an end-grain cookie)\n"
        "  radial:     vertical cut through plane y = pith + --at (quarter-sawn near 0)\n"
        "  tangential: vertical cut through plane x = pith + --at (a flat-sawn board face)\n"
        "Boards span --size WIDTHxHEIGHT with the lower edge at --bottom.");
    addCommon(slice, o->common);
    slice->add_option("--plane", o->plane, "cross | radial | tangential")
        ->check(CLI::IsMember({"cross", "radial", "tangential"}))
        ->default_val("cross");
    slice->add_option("--at", o->at, "Height of a cross cut, or board offset from the pith (m)")
        ->default_val(1.0);
    slice->add_option("--size", o->size, "Image extent WIDTHxHEIGHT in metres, e.g. 0.4x0.4m")
        ->default_val("0.4x0.4m");
    slice->add_option("--res", o->res, "Image resolution WIDTHxHEIGHT in pixels")
        ->default_val("512x512");
    slice->add_option("--bottom", o->bottom, "Boards: height of the image's lower edge (m)")
        ->default_val(0.0);
    slice->add_option("--png", o->png,
                      "Also write an 8-bit sRGB preview of the colour through OpenColorIO");
    slice
        ->add_option("--finish", o->finish,
                     "Surface finish of the cut: sawn = saw marks as on a sawn sample block "
                     "(strongest on end grain); the other presets (oiled, matte, varnished, "
                     "bare, brushed) leave a bake's colour as it is")
        ->default_val("oiled");
    const char* planeCutNote =
        " (with --right and --up: a cut through any plane, instead of --plane, --at, --size "
        "and --bottom)";
    auto* origin = slice->add_option(
        "--origin", o->origin,
        std::string("X,Y,Z: tree-space position (m) of the image's bottom-left sample") +
            planeCutNote);
    auto* right = slice->add_option("--right", o->right,
                                    "X,Y,Z: from --origin to the bottom-right sample (m)");
    auto* up = slice->add_option("--up", o->up, "X,Y,Z: from --origin to the top-left sample (m)");
    for (const char* named : {"--plane", "--at", "--size", "--bottom"})
        for (CLI::Option* general : {origin, right, up}) general->excludes(named);
    slice->callback([o] {
        SliceSpec spec;
        if (!o->origin.empty() || !o->right.empty() || !o->up.empty()) spec.cut = parsePlaneCut(*o);
        spec.plane = parseSlicePlane(o->plane);
        for (auto [value, option] : {std::pair{o->at, "--at"}, std::pair{o->bottom, "--bottom"}})
            if (!std::isfinite(value) || std::abs(value) > kMaxCoordinate)
                throw InputError("command line", option,
                                 fmt::format("expected a finite number of metres in [-{:g}, {:g}], "
                                             "found {:g}",
                                             kMaxCoordinate, kMaxCoordinate, value));
        spec.at = o->at;
        spec.bottom = o->bottom;
        std::tie(spec.width, spec.height) = parseSizeMetres(o->size, "--size");
        std::tie(spec.resX, spec.resY) = parseResolution(o->res, "--res", kMaxImageSide);
        if (!imageSizeAllowed(spec.resX, spec.resY))
            throw InputError(
                "command line", "--res",
                fmt::format("{} is over the cap of {} M pixels", o->res, kMaxImagePixels >> 20));
        BakeJob job = bakeJob(o->common, o->png);
        job.finish = o->finish;
        print(runSliceBake(job, spec));
    });
}

void addVolumeCommand(CLI::App* bake) {
    auto o = std::make_shared<VolumeOptions>();
    CLI::App* volume = bake->add_subcommand(
        "volume",
        "A 3D grid of the wood over a box, as EXR (z-slice atlas), OpenVDB (one grid per\n"
        "channel) or POV-Ray df3 (16-bit R, G, B, knot files plus a .inc pigment).\n"
        "Samples sit on the box's lattice, faces included.");
    addCommon(volume, o->common);
    volume->add_option("--box", o->box, "Tree-space box x0,y0,z0,x1,y1,z1 in metres")->required();
    volume->add_option("--res", o->res, "Samples along the box's longest edge (2..512)")
        ->default_val(64);
    volume->callback([o] {
        auto b = parseNumberList(o->box, "--box", 6);
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
                                             o->box));
        if (o->res < 2 || o->res > kMaxVolumeSide)
            throw InputError(
                "command line", "--res",
                fmt::format("expected 2 to {} samples, found {}", kMaxVolumeSide, o->res));
        spec.resolution = o->res;
        print(runVolumeBake(bakeJob(o->common, ""), spec, o->box));
    });
}

}  // namespace

void addBakeCommands(CLI::App& app) {
    CLI::App* bake =
        app.add_subcommand("bake", "Bake the wood of a skeleton into images or volumes");
    bake->require_subcommand(1);

    addSliceCommand(bake);
    addVolumeCommand(bake);
    addUvBakeCommand(bake);
}

}  // namespace nenrin
