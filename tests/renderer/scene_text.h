#pragma once
// Renderer test helpers: a scene from JSON text (written to the test's temporary folder, so
// relative paths in it resolve there) and a quiet render of it.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "renderer/path_tracer.h"
#include "renderer/scene_file.h"

namespace nenrin {

inline std::unique_ptr<Scene> sceneFromText(const std::string& name, const std::string& text) {
    std::filesystem::path path = std::filesystem::path(::testing::TempDir()) / (name + ".json");
    std::ofstream(path) << text;
    return loadScene(path.string());
}

inline Film render(const Scene& scene, int threads, RenderStats& stats) {
    RenderOptions options;
    options.threads = threads;
    options.quiet = true;
    return renderScene(scene, options, stats);
}

inline Film render(const Scene& scene, int threads = 0) {
    RenderStats stats;
    return render(scene, threads, stats);
}

}  // namespace nenrin
