// Scene files (docs/scene-format.md): read, then rendered at 4 x 3 pixels, one sample each.
// The input sits in a folder that links to the bundled scenes' skeletons, grain, meshes and
// environment maps, so the seed scenes load as they are.
#include <cmath>
#include <filesystem>

#include "fuzz/fuzz_input.h"
#include "renderer/path_tracer.h"
#include "renderer/scene_file.h"
#include "util/input_error.h"

namespace {

void linkBundledFolders() {
    for (const char* name : {"skeletons", "grain", "meshes", "env", "trees"}) {
        std::filesystem::path link = std::filesystem::path(nenrin::fuzz::inputFolder()) / name;
        std::error_code ignored;
        std::filesystem::create_directory_symlink(
            std::filesystem::path(NENRIN_SOURCE_DIR) / "scenes" / name, link, ignored);
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace nenrin;
    static const bool linked = (linkBundledFolders(), true);
    (void)linked;
    try {
        std::unique_ptr<Scene> scene = loadScene(fuzz::writeInputFile(data, size, ".json"));
        scene->settings.width = std::min(scene->settings.width, 4);
        scene->settings.height = std::min(scene->settings.height, 3);
        scene->settings.spp = 1;
        scene->settings.minSpp = 0;
        scene->settings.maxDepth = std::min(scene->settings.maxDepth, 3);
        RenderOptions options;
        options.threads = 1;
        options.quiet = true;
        RenderStats stats;
        Film film = renderScene(*scene, options, stats);
        for (float v : film.rgb)
            if (!std::isfinite(v)) fuzz::fail("a non-finite pixel in the render");
    } catch (const InputError&) {
    }
    return 0;
}
