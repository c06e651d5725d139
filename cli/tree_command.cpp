#include "tree_command.h"

#include <fmt/format.h>

#include <filesystem>
#include <string>

#include "arguments.h"
#include "renderer/colour_management.h"
#include "renderer/preview/tree_preview.h"
#include "ring_series_command.h"
#include "skeleton/skeleton_file.h"
#include "skeleton/skeleton_writer.h"
#include "skeleton/sources/measured/gran1_import.h"
#include "skeleton/sources/measured/measured_branches.h"
#include "skeleton/sources/measured/qsm_import.h"
#include "tree_model_commands.h"
#include "util/atomic_output.h"
#include "util/input_error.h"

namespace nenrin {

namespace {

namespace fs = std::filesystem;

struct ImportOptions {
    std::string input, output, format = "auto";
    double rings = 60, heightGrowth = 0, branchGrowth = 0.2, knotGamma = 0.125;
    double elongationSpeed = 0.5;
};

bool endsWith(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

/// "data/gran1", "data/gran1/Gran_1", or any of its three files -> "data/gran1/Gran_1".
std::string gran1Prefix(const std::string& input) {
    for (const char* tail : {"_pith.json", "_radii.json", "_knots.json"})
        if (endsWith(input, tail)) return input.substr(0, input.size() - std::string(tail).size());
    if (fs::is_directory(input)) {
        std::string found;
        for (const auto& e : fs::directory_iterator(input)) {
            std::string name = e.path().string();
            if (!endsWith(name, "_pith.json")) continue;
            if (!found.empty())
                throw InputError(input, "", "holds several *_pith.json logs: name one of them");
            found = name.substr(0, name.size() - std::string("_pith.json").size());
        }
        if (found.empty()) throw InputError(input, "", "no *_pith.json log in this folder");
        return found;
    }
    return input;
}

std::string detectFormat(const std::string& input) {
    if (fs::is_directory(input) || endsWith(input, "_pith.json") ||
        endsWith(input, "_radii.json") || endsWith(input, "_knots.json") ||
        fs::exists(input + "_pith.json"))
        return "gran1";
    for (const char* ext : {".txt", ".csv", ".tsv", ".dat"})
        if (endsWith(input, ext)) return "qsm";
    if (endsWith(input, ".json")) return "branches";
    throw InputError(input, "",
                     "cannot tell the format: expected a Gran_1 log (folder or *_pith.json), a "
                     "TreeQSM cylinder list (.txt/.csv), a measured-branch file (.json); or give "
                     "--format");
}

void runImport(const ImportOptions& o) {
    checkOutputName(o.output, {".json"});
    std::string format = o.format == "auto" ? detectFormat(o.input) : o.format;
    SkeletonFileInfo info;
    Skeleton skeleton;
    if (format == "gran1") {
        Gran1Options g;
        g.rings = o.rings, g.heightGrowth = o.heightGrowth, g.branchGrowth = o.branchGrowth,
        g.knotGamma = o.knotGamma;
        std::string prefix = gran1Prefix(o.input);
        Gran1Log log = importGran1(prefix, g);
        fmt::print(
            "{}: {:.2f} m log, {} knots ({} dead at once, skipped); butt radius {:.1f} mm "
            "(bark {:.1f} … {:.1f} mm) over {} rings = {:.2f} mm/year; height growth "
            "{:.2f} m/year\n",
            prefix, log.skeleton.node(log.skeleton.chain(0).segmentCount).position.z, log.knots,
            log.knotsSkipped, log.meanButtRadius * 1e3, log.minBarkRadius * 1e3,
            log.maxBarkRadius * 1e3, o.rings, log.ringWidth * 1e3, log.heightGrowth);
        fmt::print(
            "felled at {} years: set \"felling_time\": {} in the grain file to cut the "
            "log at its bark\n",
            log.fellingAge, log.fellingAge);
        info.description = "Gran_1-layout CT log imported by nenrin tree import";
        info.source = {{"model", "gran1"},
                       {"input", prefix},
                       {"rings", o.rings},
                       {"ring_width_m", log.ringWidth},
                       {"felling_age", log.fellingAge},
                       {"height_growth", log.heightGrowth},
                       {"branch_growth", o.branchGrowth},
                       {"knot_gamma", o.knotGamma}};
        skeleton = std::move(log.skeleton);
    } else if (format == "qsm") {
        QsmOptions q;
        q.elongationSpeed = o.elongationSpeed;
        QsmTree tree = importQsm(o.input, q);
        fmt::print(
            "{}: {} cylinders in {} branches; {} years at {} m/year; stem base radius "
            "{:.1f} mm = {:.2f} mm/year\n",
            o.input, tree.cylinders, tree.branches, tree.age, o.elongationSpeed,
            tree.ringWidth * tree.age * 1e3, tree.ringWidth * 1e3);
        info.description = "TreeQSM cylinder model imported by nenrin tree import";
        info.source = {{"model", "qsm"},
                       {"input", o.input},
                       {"elongation_speed", o.elongationSpeed},
                       {"age", tree.age},
                       {"ring_width_m", tree.ringWidth}};
        skeleton = std::move(tree.skeleton);
    } else if (format == "branches") {
        MeasuredTree tree = loadMeasuredTree(o.input);
        fmt::print("{}: {} measured branches, {} years at {:.3f} m/year\n", o.input,
                   tree.chainOfBranch.size(), tree.age, tree.elongationSpeed);
        info.description = "Hayashi measured-branch tree imported by nenrin tree import";
        info.source = {{"model", "measured-branches"}, {"input", o.input}, {"age", tree.age}};
        skeleton = std::move(tree.skeleton);
    } else {
        throw InputError("command line", "--format",
                         fmt::format("unknown format \"{}\": expected auto, gran1, qsm or "
                                     "branches",
                                     format));
    }
    saveSkeletonFile(skeleton, info, o.output);
    fmt::print("wrote {} ({} chains, {} segments)\n", o.output, skeleton.chains().size(),
               skeleton.segments().size());
}

struct PreviewOptions {
    std::string input, output, resolution = "800x1000";
    TreePreviewOptions preview;
};

void runPreview(PreviewOptions o) {
    checkOutputName(o.output, {".png"});
    auto [w, h] = parseResolution(o.resolution, "--res", 8192);
    o.preview.width = w, o.preview.height = h;
    Skeleton skeleton = loadSkeletonFile(o.input);
    TreePreview picture = renderTreePreview(skeleton, o.preview);
    writePreviewPng(o.output, picture.rgb, picture.width, picture.height);
    fmt::print("wrote {} ({}x{}, {} segments{})\n", o.output, w, h, picture.segments,
               picture.estimatedRadii ? "; no radii in the file: drawn from node ages" : "");
}

}  // namespace

CLI::App* addTreeCommands(CLI::App& app) {
    CLI::App* tree = app.add_subcommand(
        "tree", "Skeleton sources: grow a tree model, import a measured tree, preview a skeleton");
    tree->require_subcommand(1);

    auto io = std::make_shared<ImportOptions>();
    CLI::App* imp = tree->add_subcommand(
        "import", "Convert a measured tree to a skeleton file (docs/trees.md)");
    imp->add_option("file", io->input,
                    "Gran_1 log (folder, prefix or *_pith.json) or TreeQSM cylinder list "
                    "(.txt/.csv)")
        ->required();
    imp->add_option("-o,--output", io->output, "Output skeleton file (.json)")->required();
    imp->add_option("--format", io->format, "auto, gran1, qsm or branches (measured-branch JSON)")
        ->default_val("auto");
    imp->add_option("--rings", io->rings, "Gran_1: rings at the butt (sets the ring width)")
        ->check(finiteRange(1, 10000))
        ->default_val(60);
    imp->add_option("--height-growth", io->heightGrowth,
                    "Gran_1: m/year of height growth (0 = from the bark's taper)")
        ->check(finiteRange(0, 100))
        ->default_val(0);
    imp->add_option("--branch-growth", io->branchGrowth, "Gran_1: m/year a knot's branch grew")
        ->check(finiteRange(1e-6, 100))
        ->default_val(0.2);
    imp->add_option("--knot-gamma", io->knotGamma,
                    "Gran_1: a knot's radial speed relative to the stem")
        ->check(finiteRange(1e-6, 100))
        ->default_val(0.125);
    imp->add_option("--elongation-speed", io->elongationSpeed,
                    "QSM: m/year along every axis (QSMs carry no time)")
        ->check(finiteRange(1e-6, 100))
        ->default_val(0.5);
    imp->callback([io] { runImport(*io); });

    auto po = std::make_shared<PreviewOptions>();
    CLI::App* pre = tree->add_subcommand(
        "preview", "Picture of a skeleton: round branches with their radii (Embree curves)");
    pre->add_option("skeleton", po->input, "Skeleton file (.json)")->required();
    pre->add_option("-o,--output", po->output, "Output PNG")->required();
    pre->add_option("--res", po->resolution, "Resolution WxH")->default_val("800x1000");
    pre->add_option("--spp", po->preview.spp, "Samples per pixel")
        ->check(CLI::Range(1, 4096))
        ->default_val(16);
    pre->add_option("--azimuth", po->preview.azimuth, "Camera azimuth around the tree, degrees")
        ->check(finiteRange(-3600, 3600))
        ->default_val(30);
    pre->add_option("--elevation", po->preview.elevation, "Camera elevation, degrees")
        ->check(finiteRange(-89.0, 89.0))
        ->default_val(8);
    pre->add_option("--threads", po->preview.threads, "Worker threads (0 = all cores)")
        ->check(CLI::Range(0, 1024))
        ->default_val(0);
    pre->callback([po] { runPreview(*po); });
    addRingSeriesCommand(*tree);
    addTreeModelCommands(*tree);
    return tree;
}

}  // namespace nenrin
