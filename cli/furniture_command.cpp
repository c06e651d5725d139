#include "furniture_command.h"

#include <fmt/format.h>

#include <memory>

#include "renderer/jobs/furniture_job.h"
#include "util/input_error.h"

namespace nenrin {

void addFurnitureCommand(CLI::App& app) {
    auto job = std::make_shared<FurnitureJob>();
    auto* cmd = app.add_subcommand(
        "furniture",
        "A piece of furniture in solid wood: the model's parts (objects, groups, glTF meshes, "
        "then\n"
        "each one's connected pieces; panels over 20 cm wide glued from boards), every wood part\n"
        "its own board from the log with its fibre along the part. Writes DIR/parts.json (the\n"
        "plan: edit it and pass it back with --plan), DIR/parts/*.obj (in metres), DIR/scene.json\n"
        "(a nenrin scene of the model), DIR/preview.png rendered from it, DIR/textures/PART/ "
        "(each\n"
        "wood part's texture set) and DIR/MODEL.glb (+ .gltf, .bin: the whole model, every part\n"
        "with its set) (docs/furniture.md).");
    cmd->add_option("model", job->model, "The model: Wavefront OBJ or glTF 2.0 (.gltf, .glb)")
        ->required();
    cmd->add_option("--grain", job->grain, "Grain file of the wood (a species preset)")->required();
    cmd->add_option("-o,--output", job->output, "Output folder (created if missing)")->required();
    cmd->add_option("--skeleton", job->skeleton,
                    "The log's skeleton; default: a straight trunk 10 m tall");
    cmd->add_option("--unit", job->unit, "The model's unit: mm, cm or m")
        ->check(CLI::IsMember({"mm", "cm", "m"}))
        ->default_val("m");
    cmd->add_option("--plan", job->plan,
                    "A parts.json of an earlier run, edited: per part wood (true/false), grain, "
                    "fibre, requested_sawing (flat, quarter, mixed) and seed are taken from it");
    cmd->add_option("--grain-for", job->grainFor,
                    "MATERIAL=G.json: parts of that material (the model's material name, "
                    "parts.json's `material`) cut from that grain file; repeat for several");
    cmd->add_option("--finish", job->finish,
                    "The wood's finish: matte, oiled, varnished, bare, brushed or sawn "
                    "(docs/scene-format.md)")
        ->default_val("oiled");
    cmd->add_option("--sawing", job->sawing, "Wide faces flat-, quarter-sawn or mixed")
        ->check(CLI::IsMember({"flat", "quarter", "mixed"}))
        ->default_val("mixed");
    cmd->add_option("--seed", job->seed, "Cut plan seed: another seed, other boards")
        ->default_val(1);
    cmd->add_option("--res", job->textureSize,
                    "Texels (width and height) of each wood part's texture set, DIR/textures/; "
                    "0 = none")
        ->check(CLI::Range(0, 8192))
        ->default_val(1024);
    cmd->add_option("--preview", job->previewWidth, "Width of preview.png in pixels (height 3/4)")
        ->check(CLI::Range(16, 8192))
        ->default_val(640);
    cmd->add_option("--threads", job->threads, "Worker threads (0 = all cores)")
        ->check(CLI::Range(0, 1024))
        ->default_val(0);
    cmd->add_flag("-q,--quiet", job->quiet, "No progress bar");
    cmd->callback([job] {
        job->previewHeight = std::max(12, job->previewWidth * 3 / 4);
        for (const std::string& pair : job->grainFor) {
            const size_t eq = pair.find('=');
            if (eq == 0 || eq == std::string::npos || eq + 1 == pair.size())
                throw InputError("command line", "--grain-for",
                                 fmt::format("expected MATERIAL=GRAIN.json, found \"{}\"", pair));
            job->grainByMaterial[pair.substr(0, eq)] = pair.substr(eq + 1);
        }
        FurnitureReport report = runFurnitureJob(*job);
        for (const std::string& w : report.warnings) fmt::print(stderr, "warning: {}\n", w);
        for (const std::string& f : report.written) fmt::print("wrote {}\n", f);
        fmt::print("{} parts, {} of them wood, each its own board\n", report.parts,
                   report.woodParts);
    });
}

}  // namespace nenrin
