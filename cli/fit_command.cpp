#include "fit_command.h"

#include <fmt/format.h>

#include <filesystem>
#include <memory>

#include "fit/fit_report.h"
#include "fit/sample_file.h"
#include "fit/wood_fit.h"
#include "renderer/png_file.h"
#include "skeleton/skeleton_writer.h"
#include "util/atomic_output.h"
#include "util/input_error.h"

namespace nenrin {

namespace {

struct FitArguments {
    std::string sample, output;
    FitOptions options;
    bool noKnots = false;
};

void runFit(const FitArguments& a) {
    namespace fs = std::filesystem;
    if (fs::exists(a.output) && !fs::is_directory(a.output))
        throw InputError("command line", "-o", a.output + " exists and is not a folder");
    if (!fs::exists(a.output)) checkOutputPath(a.output);  // its parent folder is writable
    const Sample sample = loadSampleFile(a.sample);

    const WoodFit fit = fitSample(sample, a.options);

    // The folder only once there is something to put in it.
    std::error_code error;
    if (!fs::exists(a.output) && !fs::create_directories(a.output, error))
        throw InputError("command line", "-o", "cannot create the folder " + a.output);
    const std::string dir = a.output + "/";
    OutputTransaction transaction;
    SkeletonFileInfo info;
    info.description = "The pith line and ring series fitted to " + a.sample + " by nenrin fit";
    info.source = {{"model", "fit"}, {"sample", a.sample}};
    saveSkeletonFile(fit.skeleton, info, dir + "skeleton.json");
    writeTextAtomically(dir + "grain.json", fit.grain.dump(2) + '\n', "grain file");
    writeTextAtomically(dir + "fit.json", fitReport(sample, fit).dump(2) + '\n', "fit report");
    const ReportImage report = reportImage(fit);
    AtomicOutput png(dir + "report.png");
    writePng8(png.finalPath(), png.temporaryPath(), report.width, report.height, report.rgb,
              {{"Description", "nenrin fit: each photograph above the bake of its face"}});
    png.commit();
    commitOutputs();

    const PithLine& p = fit.pith;
    fmt::print(
        "pith {:.1f} mm from the sample's centre, along [{:.3f}, {:.3f}, {:.3f}]; "
        "median misfit {:.1f} deg\n",
        p.distance * 1e3, p.direction.x, p.direction.y, p.direction.z, p.medianMisfitDeg);
    fmt::print("{} rings on face {}, mean width {:.2f} mm{}\n", fit.profile.strip.rings,
               fit.profile.face, fit.grain["radial_speed"].get<double>() * 1e3,
               fit.base.empty() ? "" : "; anatomy from " + fit.base);
    for (const KnotFigures& k : fit.knots)
        fmt::print(
            "knot on face {}{}: at column {:.0f}, row {:.0f}, {:.1f} mm across; the bake's "
            "{}\n",
            k.photo.face, k.heldOut ? " (held out)" : "", k.photo.column, k.photo.row,
            2e3 * k.photo.radius,
            k.offsetMm >= 0 ? fmt::format("{:.1f} mm from it", k.offsetMm)
                            : std::string("shows none"));
    for (const FaceFigures& f : fit.faces)
        fmt::print(
            "face {}{}: rings {:.1f} deg (within 15 deg {:.0f} %), dE {:.1f}, fine {:.2f}x, "
            "mid {:.2f}x\n",
            f.name, f.heldOut ? " (held out)" : "", f.ringMedianDeg, 100 * f.ringWithin15, f.dE,
            f.fineRatio, f.midRatio);
    for (const std::string& w : fit.warnings) fmt::print(stderr, "nenrin: warning: {}\n", w);
    fmt::print("fitted in {:.1f} s; wrote {}skeleton.json, grain.json, fit.json, report.png\n",
               fit.seconds, dir);
}

}  // namespace

void addFitCommand(CLI::App& app) {
    auto a = std::make_shared<FitArguments>();
    CLI::App* cmd = app.add_subcommand(
        "fit",
        "Fit a skeleton and a grain file to photographs of a wood sample (docs/fit.md): the pith "
        "line from the rings' directions, the ring series and colours from the faces");
    cmd->add_option("sample", a->sample,
                    "The sample file: the box and, per face, its photograph and where it lies")
        ->required();
    cmd->add_option("-o,--output", a->output,
                    "Folder for skeleton.json, grain.json, fit.json and report.png")
        ->required();
    cmd->add_option("--grain", a->options.baseGrains,
                    "Grain files to take the anatomy (fibres, pores, rays) from, such as the "
                    "species presets; with several, the one whose texture matches the photos "
                    "best. The fit sets the rings and colours");
    cmd->add_option("--leave-out", a->options.heldOut,
                    "A face (by name) to leave out of the fit and only measure; repeatable");
    cmd->add_flag("--no-knots", a->noKnots,
                  "Do not look for knots (dark patches that are not knots: stains, pitch "
                  "pockets); the skeleton is the trunk alone");
    cmd->add_option("--threads", a->options.threads, "Worker threads (0 = all cores)")
        ->check(CLI::Range(0, 1024))
        ->default_val(0);
    cmd->callback([a] {
        a->options.knots = !a->noKnots;
        runFit(*a);
    });
}

}  // namespace nenrin
