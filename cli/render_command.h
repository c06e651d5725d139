#pragma once
/// `nenrin render SCENE.json -o out.exr [--spp N] [--res WxH] [--threads N] [--seed S]
/// [--png out.png] [--tile K/N] [--set POINTER=VALUE ...] [--quiet]`: the arguments become a
/// RenderJob (renderer/jobs/render_job.h).

#include <CLI/CLI.hpp>

#include "renderer/jobs/render_job.h"

namespace nenrin {

/// Runs the job and prints what was written and the summary line (render and batch).
void runRenderPrinting(const RenderJob& job);

void addRenderCommand(CLI::App& app);

}  // namespace nenrin
