#pragma once
/// `nenrin render SCENE.json -o out.exr [--spp N] [--res WxH] [--threads N] [--seed S]
/// [--png out.png] [--tile K/N] [--set POINTER=VALUE ...] [--quiet]`.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "renderer/scene_file.h"

namespace nenrin {

/// One render as the command line gives it (0 / -1 / empty: the scene's value).
struct RenderJob {
    std::string scene;
    std::string output;
    std::string png;
    std::string resolution;
    int spp = 0;
    double noiseThreshold = -1;
    int minSpp = -1;
    long long seed = -1;
    int threads = 0;
    bool quiet = false;
    std::string tile;               ///< "K/N": a split job's part
    std::vector<std::string> sets;  ///< POINTER=VALUE scene overrides
};

/// "POINTER=VALUE" strings (--set) as scene overrides; VALUE is JSON, or else a string.
SceneOverrides parseSceneOverrides(const std::vector<std::string>& sets);

/// Renders and writes the outputs, printing what was written and a summary line.
void runRender(const RenderJob& job);

void addRenderCommand(CLI::App& app);

}  // namespace nenrin
