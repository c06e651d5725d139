#include "tree_model_commands.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <string>

#include "arguments.h"
#include "skeleton/skeleton_writer.h"
#include "skeleton/sources/akagi/akagi_model.h"
#include "skeleton/sources/hayashi/hayashi_conifer.h"
#include "skeleton/sources/hayashi/hayashi_options.h"
#include "skeleton/sources/kanayama/kanayama_growth.h"
#include "skeleton/sources/kanayama/kanayama_species.h"
#include "skeleton/sources/kunii/kunii_fell.h"
#include "skeleton/sources/kunii/kunii_stand.h"
#include "skeleton/sources/kunii/kunii_stand_file.h"
#include "util/atomic_output.h"
#include "util/input_error.h"
#include "util/progress.h"

namespace nenrin {

namespace {

constexpr long long kMaxSeed = 1LL << 53;

std::string joined(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

double since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void report(const Skeleton& sk, const std::string& path) {
    size_t dead = 0;
    for (const auto& c : sk.chains())
        dead +=
            c.kind == SegmentKind::Branch && std::isfinite(sk.segment(c.firstSegment).deathTime);
    fmt::print("wrote {} ({} chains, {} segments, {} dead branches{})\n", path, sk.chains().size(),
               sk.segments().size(), dead,
               sk.ringWidths().empty()
                   ? ""
                   : fmt::format(", {} yearly ring widths", sk.ringWidths().size()));
}

struct CommonTreeOptions {
    std::string preset, output, params;
    long long seed = 1;
    int years = 0;  // 0 = the model's default
    bool quiet = false;
};

void addCommon(CLI::App* cmd, CommonTreeOptions& o, const std::string& presets,
               const std::string& defaultPreset, const std::string& yearsHelp) {
    cmd->add_option("--preset", o.preset, "Species preset: " + presets)->default_val(defaultPreset);
    cmd->add_option("--seed", o.seed, "Random seed (same seed, same tree)")
        ->check(CLI::Range(0LL, kMaxSeed))
        ->default_val(1);
    cmd->add_option("--years", o.years, yearsHelp)->check(CLI::Range(1, 500));  // as the models
    cmd->add_option("-o,--output", o.output, "Output skeleton file (.json)")->required();
}

void runHayashi(const CommonTreeOptions& o, int maxOrder) {
    checkOutputName(o.output, {".json"});
    HayashiOptions h = hayashiPreset(o.preset);
    if (!o.params.empty()) h = loadHayashiOptions(o.params, h);
    h.seed = static_cast<uint64_t>(o.seed);
    if (o.years > 0) h.years = o.years;
    h.maxOrder = maxOrder;
    auto t0 = std::chrono::steady_clock::now();
    HayashiTree tree = growHayashiConifer(h);
    fmt::print(
        "{} {}: {} years, {:.2f} m tall, {} first-order branches, crown base {:.2f} m, "
        "orders 1-{} in {:.2f} s\n",
        "hayashi", h.preset, h.years, tree.height, tree.firstOrder.size(), tree.crownBase, maxOrder,
        since(t0));
    SkeletonFileInfo info;
    info.description = fmt::format("Hayashi & Takahashi conifer ({}), {} years, seed {}", h.preset,
                                   h.years, h.seed);
    info.source = {{"model", "hayashi"}, {"options", hayashiOptionsToJson(h)}};
    saveSkeletonFile(tree.skeleton, info, o.output);
    report(tree.skeleton, o.output);
}

void runAkagi(const CommonTreeOptions& o, const std::string& table) {
    checkOutputName(o.output, {".json"});
    std::string species = table.empty() ? o.preset : table;
    auto t0 = std::chrono::steady_clock::now();
    AkagiTree tree =
        growAkagiSpecies(species, static_cast<uint64_t>(o.seed), o.years > 0 ? o.years : 30);
    fmt::print(
        "akagi {}: {:.2f} m tall, crown {:.2f} m wide, {} segments, {} leaves; {} draw(s) "
        "to a plausible tree; fit + generation {:.2f} s\n",
        species, tree.stats.height, tree.stats.crownWidth, tree.stats.segmentCount,
        tree.stats.leafCount, tree.attempts, since(t0));
    saveSkeletonFile(tree.skeleton, akagiSkeletonInfo(tree, species, static_cast<uint64_t>(o.seed)),
                     o.output);
    report(tree.skeleton, o.output);
}

void runKanayama(const CommonTreeOptions& o, int removeLeaderAt) {
    checkOutputName(o.output, {".json"});
    KanayamaOptions k =
        o.params.empty() ? kanayamaPreset(o.preset) : readKanayamaOptionsFile(o.params);
    k.seed = static_cast<uint64_t>(o.seed);
    if (o.years > 0) k.years = o.years;
    if (removeLeaderAt >= 0) k.removeLeaderAtYear = removeLeaderAt;
    validateKanayamaOptions(k);  // before the progress line starts
    auto t0 = std::chrono::steady_clock::now();
    ProgressReporter progress(k.years, "Growing " + k.preset, o.quiet);
    KanayamaTree tree = growKanayamaTree(k, [&](int, int) { progress.advance(); });
    progress.done();
    fmt::print(
        "kanayama {}: {} years, {:.2f} m tall, trunk radius {:.1f} mm, {} shoots ({} died "
        "of shade), {} dormant buds broke; {:.2f} s ({:.2f} s light)\n",
        k.preset, k.years, tree.height(),
        tree.stats.trunkBaseRadiusPerYear.empty() ? 0.0
                                                  : tree.stats.trunkBaseRadiusPerYear.back() * 1e3,
        tree.shoots.size(), tree.stats.shootDeaths, tree.stats.dormantBudsBroken, since(t0),
        tree.stats.lightSeconds);
    SkeletonFileInfo info;
    info.description = fmt::format("Kanayama growth simulation ({}), {} years, seed {}", k.preset,
                                   k.years, k.seed);
    info.source = {{"model", "kanayama"},
                   {"preset", k.preset},
                   {"seed", k.seed},
                   {"years", k.years},
                   {"remove_leader_at_year", k.removeLeaderAtYear}};
    saveSkeletonFile(tree.skeleton, info, o.output);
    report(tree.skeleton, o.output);
}

}  // namespace

void addTreeModelCommands(CLI::App& tree) {
    auto hayashi = std::make_shared<CommonTreeOptions>();
    auto maxOrder = std::make_shared<int>(2);
    CLI::App* h = tree.add_subcommand(
        "hayashi", "Hayashi & Takahashi's spiral conifer (sugi, hinoki) or whorled pine");
    addCommon(h, *hayashi, joined(hayashiPresetNames()), "sugi", "Age of the tree (default 20)");
    h->add_option("--max-order", *maxOrder,
                  "Branch orders to grow: 1-2 for wood (knots); 3-4 add twigs and foliage for "
                  "previews (a 20-year sugi with 4 orders has ~380k segments, ~100 MB of JSON)")
        ->check(CLI::Range(1, 4))
        ->default_val(2);
    h->add_option("--params", hayashi->params,
                  "JSON file of option overrides (docs/tree-hayashi.md)");
    h->callback([hayashi, maxOrder] { runHayashi(*hayashi, *maxOrder); });

    auto akagi = std::make_shared<CommonTreeOptions>();
    auto table = std::make_shared<std::string>();
    CLI::App* a = tree.add_subcommand(
        "akagi",
        "Akagi & Kitajima's 13-parameter tree, parameters drawn from a hierarchical-Bayes fit "
        "of a species table");
    addCommon(a, *akagi, joined(akagiSpeciesNames()) + " (illustrative tables)", "keyaki",
              "Years of growth the tree stands for (default 30)");
    a->add_option("--table", *table,
                  "Fit your own observation table (CSV, docs/tree-akagi.md) instead of a preset");
    a->callback([akagi, table] { runAkagi(*akagi, *table); });

    auto kanayama = std::make_shared<CommonTreeOptions>();
    auto removeLeader = std::make_shared<int>(-1);
    CLI::App* k = tree.add_subcommand(
        "kanayama", "Kanayama, Sakata & Masuyama's light + hormone growth simulation");
    addCommon(k, *kanayama, joined(kanayamaPresetNames()), "cherry",
              "Years to simulate (default 15)");
    k->add_option("--params", kanayama->params,
                  "JSON options file instead of a preset (docs/tree-kanayama.md)");
    k->add_option("--remove-leader-at", *removeLeader,
                  "Cut the main stem at the start of this year (dormant buds break)")
        ->check(CLI::Range(0, 500));
    k->add_flag("-q,--quiet", kanayama->quiet, "No progress bar");
    k->callback([kanayama, removeLeader] { runKanayama(*kanayama, *removeLeader); });
}

namespace {

struct StandCliOptions {
    std::string preset, output;
    int trees = 100, years = 100;
    long long seed = 1;
    double irradiance = -1;
    bool quiet = false;
};

void runStand(const StandCliOptions& o) {
    checkOutputName(o.output, {".json"});
    StandOptions s = standPreset(o.preset);
    s.trees = o.trees;
    s.years = o.years;
    s.seed = static_cast<uint64_t>(o.seed);
    if (o.irradiance >= 0) {
        s.irradiance = o.irradiance;
        s.schedule.clear();
    }
    validateStandOptions(s);  // before the progress line starts
    auto t0 = std::chrono::steady_clock::now();
    ProgressReporter progress(s.years, "Growing the stand", o.quiet);
    Stand stand = simulateStand(s, [&](int, int) { progress.advance(); });
    progress.done();
    size_t alive = 0;
    for (const auto& t : stand.trees) alive += t.deathYear == kStillAlive;
    StandComposition c = standComposition(stand, 0.5);
    fmt::print(
        "stand {}: {} years, {} trees ever, {} alive; biomass share of shade-tolerant "
        "species (g < 0.5) {:.2f}; {:.2f} s\n",
        o.preset, s.years, stand.trees.size(), alive, c.tolerantShare(), since(t0));
    saveStandFile(stand, o.output);
    // A young stand has no tree old enough to call suppressed: said, not an error (the stand
    // is fine; `stand fell --tree suppressed` explains the same).
    auto pick = [&](TreePick which) {
        try {
            return std::to_string(pickStandTree(stand, which));
        } catch (const InputError&) {
            return std::string("none yet");
        }
    };
    fmt::print(
        "wrote {}\ndominant tree: {}, most suppressed living tree (>= 20 years old): {} (nenrin "
        "stand fell {} --tree ID -o tree.json)\n",
        o.output, pick(TreePick::Dominant), pick(TreePick::Suppressed), o.output);
}

void runFell(const std::string& input, const std::string& which, const std::string& output) {
    checkOutputName(output, {".json"});
    Stand stand = loadStandFile(input);
    uint32_t id = 0;
    if (which == "dominant" || which == "suppressed") {
        id = pickStandTree(stand, treePickFromName(which));
    } else {
        try {
            size_t used = 0;
            long long v = std::stoll(which, &used);
            if (used != which.size() || v < 0) throw std::invalid_argument(which);
            id = static_cast<uint32_t>(v);
        } catch (const std::exception&) {
            throw InputError("command line", "--tree",
                             fmt::format("\"{}\" is not a tree id: expected a number or {}", which,
                                         joined(treePickNames())));
        }
    }
    Skeleton tree = fellStandTree(stand, id, {});
    const StandTree& t = stand.trees.at(id);
    fmt::print(
        "tree {}: species g = {:.2f}, born year {}, {}, {:.1f} m tall, stem radius "
        "{:.1f} mm\n",
        id, t.species, t.birthYear,
        t.deathYear == kStillAlive ? std::string("alive")
                                   : fmt::format("died year {}", t.deathYear),
        t.history.back().height, t.history.back().stemRadius * 1e3);
    SkeletonFileInfo info;
    info.description = fmt::format("Tree {} felled from stand {}", id, input);
    info.source = {{"model", "kunii"}, {"stand", input}, {"tree", id}, {"species_g", t.species}};
    saveSkeletonFile(tree, info, output);
    report(tree, output);
}

}  // namespace

void addStandCommands(CLI::App& app) {
    CLI::App* stand = app.add_subcommand(
        "stand", "Forest stands of interacting trees (Im, Shinagawa & Kunii); fell a tree");
    stand->require_subcommand(1);
    auto o = std::make_shared<StandCliOptions>();
    CLI::App* kunii =
        stand->add_subcommand("kunii", "Simulate a stand year by year (docs/stand-kunii.md)");
    kunii->add_option("--preset", o->preset, "Stand preset: " + joined(standPresetNames()))
        ->default_val("tropical");
    kunii->add_option("--trees", o->trees, "Seedlings at year 0")
        ->check(CLI::Range(1, 100000))
        ->default_val(100);
    kunii->add_option("--years", o->years, "Years to simulate")
        ->check(CLI::Range(1, 5000))
        ->default_val(100);
    kunii->add_option("--seed", o->seed, "Random seed")
        ->check(CLI::Range(0LL, kMaxSeed))
        ->default_val(1);
    kunii
        ->add_option("--irradiance", o->irradiance,
                     "Above-canopy irradiance I0 (1 = full sun), replacing the preset's")
        ->check(finiteRange(0.0, 100.0));
    kunii->add_option("-o,--output", o->output, "Output stand file (.json)")->required();
    kunii->add_flag("-q,--quiet", o->quiet, "No progress bar");
    kunii->callback([o] { runStand(*o); });

    auto input = std::make_shared<std::string>(), which = std::make_shared<std::string>(),
         output = std::make_shared<std::string>();
    CLI::App* fell = stand->add_subcommand(
        "fell", "Turn one tree of a stand into a skeleton whose rings follow its life");
    fell->add_option("stand", *input, "Stand file (.json)")->required();
    fell->add_option("--tree", *which, "Tree id, or dominant / suppressed")->required();
    fell->add_option("-o,--output", *output, "Output skeleton file (.json)")->required();
    fell->callback([input, which, output] { runFell(*input, *which, *output); });
}

}  // namespace nenrin
