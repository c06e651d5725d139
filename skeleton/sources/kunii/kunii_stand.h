#pragma once
/// Im, Shinagawa & Kunii's forest of interacting trees: a stand simulated year by year, every
/// tree keeping the record of its life (weight, height, crown, stem radius, light) so that any
/// tree can later be felled into a skeleton whose rings follow that life (kunii_fell.h).
///
/// Each year: the light of every living tree is integrated over its cylindrical crown (eq. 4),
/// minus the shade of every neighbour whose projected crown circle overlaps it; lower crown
/// layers below the compensation point are shed (the crown base rises); trees whose crown gets
/// less than their compensation point die; the others grow by eq. 1 (kunii_growth_law.h);
/// seedlings germinate at seeded positions where the light on the ground exceeds a threshold.
/// The plot is square and periodic. See docs/stand-kunii.md.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "skeleton/sources/kunii/kunii_growth_law.h"

namespace nenrin {

/// A point of the above-canopy irradiance schedule: I0 = `irradiance` at `year`, linear in
/// between, constant before the first and after the last key.
struct IrradianceKey {
    double year = 0;
    double irradiance = 1;
};

/// Weight -> size relations. D is the stem diameter at the base (m):
///   height        H(D) = maxHeight (1 - exp(-heightSlope D / maxHeight))
///   crown radius  R(D) = crownRadiusCoefficient D^crownRadiusExponent
///   weight        w(D) = stemDensity (pi/4) D^2 H(D)           (kg; stemDensity = wood
///                                                               density x form factor)
struct KuniiAllometry {
    double maxHeight = 35;              ///< m
    double heightSlope = 100;           ///< m of height per m of diameter, for small trees
    double crownRadiusCoefficient = 8;  ///< m
    double crownRadiusExponent = 0.7;
    double stemDensity = 300;    ///< kg/m^3 (600 kg/m^3 wood x 0.5 form factor)
    double maxCrownRatio = 0.6;  ///< crown depth / height at most (natural pruning)
    double minCrownRatio = 0.1;  ///< crown depth / height at least (shade cannot shed more)

    double height(double diameter) const;
    double crownRadius(double diameter) const;
    double weight(double diameter) const;
    /// Inverse of weight(): the diameter of a tree of weight w.
    double diameter(double weight) const;
};

struct StandOptions {
    int trees = 100;                      ///< trees at year 0 (seedlings at random positions)
    int years = 100;                      ///< years simulated
    uint64_t seed = 1;                    ///< < 2^53, so that stand files hold it exactly
    double plotSize = 40;                 ///< m, side of the square periodic plot
    double irradiance = 1;                ///< I0, relative (1 = full sun), when `schedule` is empty
    std::vector<IrradianceKey> schedule;  ///< I0 over the years (hysteresis experiments)

    KuniiGrowthLaw law;
    KuniiAllometry allometry;
    double crownDensity = 0.2;     ///< t of eq. 4: light attenuation per m of crown (1/m)
    double crownTransmission = 1;  ///< k of eq. 4: I at the crown top = k I0
    int crownLayers = 8;           ///< layers of the crown light integral

    double speciesMin = 0.05;  ///< g range of the species drawn (uniformly)
    double speciesMax = 1.0;

    double seedlingDiameter = 0.005;  ///< m, stem diameter of a new seedling
    double referenceWeight = 1;       ///< kg: eq. 1 gives the rate of a tree this heavy
    double maxWeight = 5000;          ///< kg: growth stops here (ontogenetic limit)
    /// Seeded positions tried for germination each year, per 100 m^2 of plot.
    double germinationAttempts = 0.25;
    /// Seedlings appear only where the light on the ground exceeds this (relative irradiance).
    double germinationLight = 0.2;
    /// Consecutive years below the compensation point that kill a tree (the paper: 1).
    int yearsBelowCompensation = 1;

    /// I0 in `year` (the schedule, or the constant irradiance).
    double irradianceAt(double year) const;
};

/// Named stand set-ups (the experiments of docs/stand-kunii.md):
///   "tropical" - the defaults: full sun (I0 = 1), 100 years;
///   "shade"    - I0 = 0.3 (a cool, dim climate: shade-tolerant species take over);
///   "cooling"  - 50 years at I0 = 1, down to 0.35 by year 60, 120 years in all;
///   "warming"  - 50 years at I0 = 0.25, up to 0.35 by year 60, 120 years in all
///                (cooling and warming end at the same I0 with different species: hysteresis).
/// Throws InputError for an unknown name.
StandOptions standPreset(const std::string& name);
std::vector<std::string> standPresetNames();

/// Throws InputError naming the parameter when an option is out of range.
void validateStandOptions(const StandOptions& options);

/// State of a tree at the end of one year, and the light it received during it.
struct TreeYear {
    double weight = 0;       ///< kg
    double height = 0;       ///< m
    double crownBase = 0;    ///< m above ground
    double crownRadius = 0;  ///< m
    double stemRadius = 0;   ///< m, at the base
    double irradiance = 0;   ///< crown-mean irradiance that year (relative), eq. 1's I
};

inline constexpr int kStillAlive = -1;

struct StandTree {
    uint32_t id = 0;
    double species = 0;           ///< g
    double x = 0, y = 0;          ///< m, position in the plot
    int birthYear = 0;            ///< first year the tree grew
    int deathYear = kStillAlive;  ///< year it died (it did not grow that year), or kStillAlive
    TreeYear initial;             ///< the seedling, before its first year (irradiance 0)
    /// Ground light where it germinated (relative irradiance); -1 for the trees of year 0.
    double germinationLight = -1;
    /// history[k] = end of year birthYear + k; size = (deathYear or years) - birthYear.
    std::vector<TreeYear> history;

    bool alive() const { return deathYear == kStillAlive; }
    const TreeYear& last() const { return history.empty() ? initial : history.back(); }
};

struct Stand {
    StandOptions options;
    std::vector<StandTree> trees;    ///< every tree that ever lived, by id
    std::vector<double> irradiance;  ///< I0 of each year
};

Stand simulateStand(const StandOptions& options,
                    const std::function<void(int year, int years)>& progress = {});

/// Total weight of the living trees at the end, split at species g = `split`.
struct StandComposition {
    double tolerantWeight = 0;    ///< g <  split
    double intolerantWeight = 0;  ///< g >= split
    double meanSpecies = 0;       ///< weight-weighted mean g
    int living = 0;
    double tolerantShare() const {
        double t = tolerantWeight + intolerantWeight;
        return t > 0 ? tolerantWeight / t : 0;
    }
};
/// Composition of the living stand at the end of `year` (default: the last year).
StandComposition standComposition(const Stand& stand, double split, int year = -1);

/// Light on the ground at (x, y) at the end of `year`, under the crowns of the trees living
/// then, computed from the stand's records: I0 (1 - sum over covering crowns of
/// (1 - exp(-t crown depth))), at least 0. Seedlings germinate where this exceeds
/// StandOptions::germinationLight.
double groundLight(const Stand& stand, double x, double y, int year);

/// The state of a tree at the end of `year`, or nullptr if it was not alive then.
const TreeYear* treeStateAt(const StandTree& tree, int year);

}  // namespace nenrin
