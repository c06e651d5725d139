#pragma once
/// Parameters of Kanayama, Sakata & Masuyama's growth model (light + hormone + branching, one
/// step per year; docs/tree-kanayama.md), the species presets (cherry, zelkova, azalea) and
/// strict JSON overrides.
///
/// Units: metres, years, radians in the structs (degrees in JSON files, keys ending in "Deg").
/// Hormone amounts are in units of the production of a fully lit new shoot (dH = 1 by default);
/// "vigour" is a shoot's hormone relative to the steady state of a fully lit leader,
/// H_ref = dH / (1 - beta alpha_t), so a well-lit leader has vigour ~1.

#include <cstdint>
#include <string>
#include <vector>

namespace nenrin {

class JsonReader;

enum class KanayamaBranching { Monopodial, Sympodial };

/// One species: the parameters the paper lists for its light, hormone and branching models.
struct KanayamaSpecies {
    // Light environment (leaf spheres under a sky dome).
    double leafSize = 0.06;    ///< m: leaf-sphere radius of a shoot of zero length
    double extinction = 1.5;   ///< 1/m: light extinction inside a leaf sphere (Beer-Lambert)
    double deathLight = 0.25;  ///< a new shoot dies when its light is below this (1 = open sky)
    double deathJitter = 0.3;  ///< relative spread of the seeded death threshold (+-)

    // Hormone (one imaginary auxin-like hormone, paper 2.2).
    double alphaTerminal = 1.0;   ///< inheritance rate of a terminal shoot
    double alphaLateral = 0.4;    ///< inheritance rate of a lateral shoot
    double beta = 0.7;            ///< fraction of last year's hormone a shoot keeps
    double gamma = 0.5;           ///< transfer rate from a shoot to its parent
    double production = 1.0;      ///< dH: production of a new shoot at full light
    double maxVigour = 1.6;       ///< cap on a shoot's vigour (old shoots pool much hormone)
    double seedlingVigour = 1.0;  ///< vigour the first shoot inherits from the seed

    // Branching (paper 2.3).
    KanayamaBranching branching = KanayamaBranching::Monopodial;
    int shortShootNodes = 2;         ///< nodes of a short shoot
    int longShootMaxNodes = 10;      ///< nodes of a long shoot at vigour 1
    double shortInternode = 0.005;   ///< m
    double longInternodeMax = 0.03;  ///< m, at vigour 1
    double longShootVigour = 0.55;   ///< vigour above which a shoot grows long (apical dominance)
    int terminalLateralBuds = 1;     ///< buds beside the terminal bud (they break next year)
    int lateralBudsPerNode = 1;      ///< axillary buds per node
    double phyllotaxis = 2.513;      ///< rad: divergence angle between consecutive nodes
    double lateralAngle = 0.8;       ///< rad: angle between a lateral shoot and its parent
    double sympodialBend = 0.35;     ///< rad: bend at the node where a sympodial axis continues
    double gravitropism = 0.08;      ///< per-internode turn towards +Z at vigour 1
    double phototropism = 0.08;      ///< per-internode turn towards the brightest direction
    double budBreak = 2.0;           ///< axillary buds breaking next year on a vigour-1 shoot
    double budBreakAgeStart = 1.0;   ///< multiplier of budBreak in year 0 ...
    double budBreakAgeRate = 0.0;    ///< ... plus this per year (capped at 1): age change
    int leavesPerNode = 1;
    double initialArea = 3e-6;      ///< m^2: cross-section of a new shoot
    double areaPerLeaf = 1.5e-6;    ///< m^2 per leaf carried above, per year (pipe-like)
    double seasonFraction = 0.5;    ///< share of the year in which shoots elongate
    double directionJitter = 0.05;  ///< rad: seeded wobble of each new shoot's direction

    // Dormant buds.
    double dormantBreakVigour = 1e6;  ///< an old shoot above this vigour breaks dormant buds
    double dormantDropRatio =
        0.6;  ///< ... or when lost branches above took more than 1 - this of its inflow
    int dormantBreakCount = 2;  ///< dormant buds one shoot breaks per event
    int dormantLifetime = 8;    ///< years a dormant bud stays able to break
};

/// Simulation options: the species plus the run's seed, length and experiment switches.
struct KanayamaOptions {
    std::string preset = "cherry";
    KanayamaSpecies species;
    uint64_t seed = 1;
    int years = 15;
    int removeLeaderAtYear = -1;  ///< cut the main stem at the start of this year (-1: never)
    int removeLeaderShoots = 2;   ///< how many of the stem's newest yearly shoots are cut
    double skyBrightness = 1.0;   ///< multiplies the light every shoot receives
    int skyDirections = 64;       ///< dome directions (stratified, CIE overcast weights)
    bool referenceLight = false;  ///< O(n^2) sphere projection instead of Embree rays
    int threads = 0;  ///< worker threads for the light (0 = all); results do not depend on it
};

/// "cherry", "zelkova", "azalea".
std::vector<std::string> kanayamaPresetNames();
/// The preset's options (15 years, seed 1). Unknown names throw InputError.
KanayamaOptions kanayamaPreset(const std::string& name);
/// Throws InputError naming the parameter (and `file` if given) for values out of range.
void validateKanayamaOptions(const KanayamaOptions& options, const std::string& file = "");
/// Reads options from a strict JSON object: optional "preset" (applied first), "seed", "years",
/// "removeLeaderAtYear", "skyBrightness", "skyDirections", "referenceLight", "threads" and a
/// "species" object with any KanayamaSpecies field (angles as "<name>Deg"). Unknown keys throw.
KanayamaOptions readKanayamaOptions(JsonReader& reader);
/// readKanayamaOptions on a file.
KanayamaOptions readKanayamaOptionsFile(const std::string& path);

}  // namespace nenrin
