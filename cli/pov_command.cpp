#include "pov_command.h"

#include <fmt/format.h>

#include "arguments.h"
#include "renderer/pov/pov_export.h"
#include "renderer/scene_file.h"
#include "util/memory_budget.h"

namespace nenrin {

namespace {

struct PovOptions {
    std::string scene, output;
    int volume = 128, threads = 0;
    bool quiet = false;
};

}  // namespace

void addPovCommands(CLI::App& app) {
    auto p = std::make_shared<PovOptions>();
    CLI::App* pov = app.add_subcommand(
        "pov",
        "Write a scene's twin for POV-Ray 3.7: scene.pov, scene.ini and df3 volumes of "
        "the wood (docs/povray-bridge.md)");
    pov->add_option("scene", p->scene, "Scene JSON file")->required();
    pov->add_option("-o,--output", p->output, "Existing folder for the POV-Ray files")->required();
    pov->add_option("--volume", p->volume, "df3 samples along a wood object's longest side")
        ->check(CLI::Range(2, 1024))
        ->default_val(128);
    pov->add_option("--threads", p->threads, "Worker threads (0 = all cores)")
        ->check(CLI::Range(0, 1024))
        ->default_val(0);
    pov->add_flag("-q,--quiet", p->quiet, "No progress output");
    addMaxMemoryOption(pov);
    pov->callback([p] {
        auto scene = loadScene(p->scene);
        PovExportOptions options;
        options.volumeResolution = p->volume;
        options.threads = p->threads;
        options.quiet = p->quiet;
        const PovOutputSize size = povOutputSize(*scene, options);
        if (size.volumes > 0)
            fmt::print("writing {} of df3 volumes ({} wood object{} at --volume {})\n",
                       formatBytes(size.bytes), size.volumes, size.volumes == 1 ? "" : "s",
                       options.volumeResolution);
        for (const auto& f : exportPovScene(*scene, p->output, options))
            fmt::print("wrote {}\n", f);
    });
}

}  // namespace nenrin
