#pragma once
/// The yearly step of Kanayama, Sakata & Masuyama's growth model (paper 3):
///   (1) break buds, grow new shoots provisionally; (2) light on every new shoot's leaf sphere,
///   shoots below a seeded, jittered threshold die; (3) hormone from light, transported to the
///   root; (4) elongate and bend (gravitropism, phototropism) with node count, internode length
///   and tropism strength scaled by hormone; (5) next year's buds, dormant-bud release.
/// Thickening: every living shoot's cross-section grows by areaPerLeaf x the leaves it carries.
/// The result is the shoot history plus a Skeleton (kanayama_skeleton.h) for the grain.

#include <cstdint>
#include <functional>
#include <vector>

#include "skeleton/skeleton.h"
#include "skeleton/sources/kanayama/kanayama_species.h"

namespace nenrin {

/// One year's growth of one bud: a shoot of `nodes.size() - 1` internodes.
struct KanayamaShoot {
    int32_t parent = kNone;       ///< parent shoot, kNone for the seedling
    int parentNode = 0;           ///< node of the parent the shoot starts at (1..parent's count)
    int year = 0;                 ///< the year it grew
    bool terminal = false;        ///< continues its parent's axis (terminal or sympodial leader)
    bool fromDormantBud = false;  ///< broke from a bud that had been dormant >= 1 year
    bool longShoot = false;
    std::vector<Vec3> nodes;  ///< nodes[0] = start (on the parent), then one per node
    double length = 0;        ///< m
    int leaves = 0;
    double light = 0;  ///< received light (L) in its growth year
    double deathThreshold = 0;
    double hormone = 0;  ///< at the end of the latest year it was alive
    double vigour = 0;   ///< hormone / H_ref in its growth year
    double area = 0;     ///< m^2: cross-section now (or when it died)
    bool alive = true;
    bool removed = false;           ///< cut off (leader removal): not in the wood
    double deathTime = kNeverDies;  ///< years
};

struct KanayamaStats {
    std::vector<double> heightPerYear;           ///< m, at the end of each year
    std::vector<int> newShootsPerYear;           ///< buds broken (= leaf spheres lit) per year
    std::vector<double> trunkBaseRadiusPerYear;  ///< m, at the end of each year
    int dormantBudsBroken = 0;  ///< shoots from buds that had been dormant >= 1 year
    int shootDeaths = 0;        ///< new shoots killed by low light
    int branchDeaths = 0;       ///< older shoots that died when they lost all leaves above
    double lightSeconds = 0;    ///< wall time in the light model
};

struct KanayamaTree {
    Skeleton skeleton;
    KanayamaStats stats;
    std::vector<KanayamaShoot> shoots;  ///< parents precede children
    double height() const { return stats.heightPerYear.empty() ? 0 : stats.heightPerYear.back(); }
};

/// Runs the simulation. Invalid options throw InputError. `progress(year, years)` is called
/// after every year. Same options => bitwise the same tree, whatever the thread count.
KanayamaTree growKanayamaTree(const KanayamaOptions& options,
                              const std::function<void(int year, int years)>& progress = {});

}  // namespace nenrin
