// nenrin: solid-texture wood from Momoi's growth-time field. Thin main: subcommands live in
// their own files; user errors arrive here as InputError and leave as one line + exit code 1.

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "bake_command.h"
#include "compare_command.h"
#include "denoise_command.h"
#include "farm_command.h"
#include "fit_command.h"
#include "furniture_command.h"
#include "grain_command.h"
#include "pov_command.h"
#include "render_command.h"
#include "split_commands.h"
#include "stats_command.h"
#include "tree_command.h"
#include "tree_model_commands.h"
#include "util/atomic_output.h"
#include "util/input_error.h"

int main(int argc, char** argv) {
    // Before any thread starts: a killed command leaves no temporary output behind.
    nenrin::removeOutputsOnSignals();
    CLI::App app{"nenrin " NENRIN_VERSION
                 " - wood that grew: growth-time rings around knots, baked and rendered"};
    app.set_version_flag("--version", NENRIN_VERSION);
    app.require_subcommand(1);
    nenrin::addBakeCommands(app);
    nenrin::addGrainCommands(app);
    nenrin::addRenderCommand(app);
    nenrin::addDenoiseCommand(app);
    nenrin::addMergeCommand(app);
    nenrin::addBatchCommand(app);
    nenrin::addFarmCommand(app);
    nenrin::addPovCommands(app);
    nenrin::addCompareCommand(app);
    nenrin::addTreeCommands(app);
    nenrin::addStandCommands(app);
    nenrin::addStatsCommand(app);
    nenrin::addFurnitureCommand(app);
    nenrin::addFitCommand(app);
    try {
        // Every output of the command reaches its final name only if the command succeeds.
        nenrin::OutputTransaction outputs;
        app.parse(argc, argv);
        nenrin::commitOutputs();
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const nenrin::InputError& e) {
        fmt::print(stderr, "nenrin: error: {}\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        fmt::print(stderr, "nenrin: error: {}\n", e.what());
        return 1;
    }
    return 0;
}
