#include "uv_bake_command.h"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>

#include "arguments.h"
#include "renderer/scene_file.h"
#include "renderer/texture_set/gltf_texture_set.h"
#include "renderer/texture_set/texture_set_files.h"
#include "renderer/texture_set/uv_bake.h"
#include "util/input_error.h"

namespace nenrin {

namespace {

struct UvBakeCliOptions {
    std::string scene, object, output;
    int resolution = 2048, padding = 8, threads = 0;
    bool quiet = false, gltf = false;
};

void run(const UvBakeCliOptions& o) {
    namespace fs = std::filesystem;
    if (!fs::is_directory(o.output))
        throw InputError("command line", "-o",
                         fmt::format("\"{}\" is not an existing folder for the maps", o.output));
    std::unique_ptr<Scene> scene = loadScene(o.scene);
    const SceneObject* object = nullptr;
    std::string names;
    for (const SceneObject& so : scene->objects) {
        if (so.name == o.object) object = &so;
        names += (names.empty() ? "\"" : ", \"") + so.name + "\"";
    }
    if (!object)
        throw InputError(o.scene, "objects",
                         fmt::format("no object named \"{}\" (the scene has {})", o.object, names));

    UvBakeOptions options;
    options.width = options.height = o.resolution;
    options.padding = o.padding;
    options.threads = o.threads;
    options.quiet = o.quiet;
    auto t0 = std::chrono::steady_clock::now();
    UvMaps maps = bakeUvMaps(*scene, *object, options);
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    const UvRaster& r = maps.raster;
    // Layout problems are reported, not fatal: the maps are still usable where they are valid.
    if (r.overlappingTexels > 0)
        fmt::print(stderr,
                   "nenrin: warning: {}: {} texels are covered by more than one triangle "
                   "(overlapping UVs): those show one of the surfaces\n",
                   o.object, r.overlappingTexels);
    if (r.trianglesOutsideUnitSquare > 0)
        fmt::print(stderr,
                   "nenrin: warning: {}: {} triangles have UVs outside [0,1]: only their "
                   "part inside the map is baked\n",
                   o.object, r.trianglesOutsideUnitSquare);
    if (r.degenerateTriangles > 0)
        fmt::print(stderr, "nenrin: warning: {}: {} triangles have no UV area and were skipped\n",
                   o.object, r.degenerateTriangles);

    std::map<std::string, std::string> metadata{{"version", NENRIN_VERSION},
                                                {"scene", o.scene},
                                                {"object", o.object},
                                                {"padding", std::to_string(o.padding)}};
    // Inside the command's output transaction (cli/main.cpp): a failure in the glTF files
    // leaves none of the set behind.
    std::vector<std::string> files = writeTextureSet(maps, *object, o.output, metadata);
    if (o.gltf) {
        std::vector<std::string> gltf =
            writeGltfTextureSet(maps, *object, o.output, metadata).written;
        files.insert(files.end(), gltf.begin(), gltf.end());
    }
    for (const auto& f : files) fmt::print("wrote {}\n", f);
    size_t covered = 0;
    for (int32_t t : r.triangle) covered += t >= 0;
    fmt::print("{}x{} texels, {:.1f}% covered by {} triangles, {} texels of padding, in {:.2f} s\n",
               maps.width, maps.height, 100.0 * covered / r.triangle.size(),
               object->mesh->triangles.size(), o.padding, seconds);
}

}  // namespace

void addUvBakeCommand(CLI::App* bake) {
    auto o = std::make_shared<UvBakeCliOptions>();
    CLI::App* cmd = bake->add_subcommand(
        "uv",
        "Bake a wood mesh of a scene onto its UV layout as linear EXR maps (basecolor, "
        "coverage, roughness, normal, fibre, growth) with NAME.obj/NAME.mtl and "
        "texture-set.json; with --gltf also glTF 2.0 (NAME.gltf/.bin/.glb, PNG textures). "
        "See docs/uv-bake.md");
    cmd->add_option("--scene", o->scene, "Scene JSON file (docs/scene-format.md)")->required();
    cmd->add_option("--object", o->object, "Name of a mesh object with a wood material")
        ->required();
    cmd->add_option("--res", o->resolution, "Map width and height in texels")
        ->check(CLI::Range(1, kMaxImageSide))
        ->default_val(2048);
    cmd->add_option("--padding", o->padding, "Texels of gutter grown past the UV charts")
        ->check(CLI::Range(0, 256))
        ->default_val(8);
    cmd->add_option("-o,--output", o->output, "Existing folder for the maps")->required();
    cmd->add_option("--threads", o->threads, "Worker threads (0 = all cores)")
        ->check(CLI::Range(0, 1024))
        ->default_val(0);
    cmd->add_flag("--gltf", o->gltf,
                  "Also write glTF 2.0: NAME.gltf + NAME.bin and NAME.glb with PNG textures, the "
                  "coat as KHR_materials_clearcoat, the fibres as KHR_materials_anisotropy");
    cmd->add_flag("-q,--quiet", o->quiet, "No progress bar");
    addMaxMemoryOption(cmd);
    cmd->callback([o] { run(*o); });
}

}  // namespace nenrin
