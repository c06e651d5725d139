#include "skeleton/sources/kunii/kunii_fell.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "util/input_error.h"

namespace nenrin {

namespace {

constexpr int kSuppressedMinAge = 20;
constexpr int kSuppressedWindow = 10;
/// A living limb at the very top reaches this fraction of the crown radius.
constexpr double kTopReach = 0.1;

/// A tree's state by age: age 0 = the seedling, age k = end of its year k - 1.
class Life {
public:
    explicit Life(const StandTree& t) : t_(t) {}
    int years() const { return static_cast<int>(t_.history.size()); }
    const TreeYear& at(int age) const {
        return age <= 0 ? t_.initial : t_.history[static_cast<size_t>(std::min(age, years()) - 1)];
    }
    /// The age (fractional: linear within the year) when the leader reached height z.
    double ageAtHeight(double z) const {
        if (z <= at(0).height) return 0;
        for (int a = 1; a <= years(); ++a) {
            double h0 = at(a - 1).height, h1 = at(a).height;
            if (z <= h1) return h1 > h0 ? a - 1 + (z - h0) / (h1 - h0) : a;
        }
        return years();
    }
    /// The first age at which the crown base stood at or above z, or -1 if it never did.
    int ageCrownBasePassed(double z) const {
        for (int a = 0; a <= years(); ++a)
            if (at(a).crownBase >= z) return a;
        return -1;
    }
    /// Stem radius at a fractional age (linear within the year).
    double stemRadius(double age) const {
        int a = static_cast<int>(std::floor(age));
        double u = age - a;
        return at(a).stemRadius * (1 - u) + at(a + 1).stemRadius * u;
    }

private:
    const StandTree& t_;
};

/// A first-order lateral and everything on it.
struct Limb {
    double born = 0;            ///< age the leader passed its fork
    double stop = 0;            ///< age it stopped growing: its death, or the felling
    double death = kNeverDies;  ///< age the crown base passed it
    double reach = 0;           ///< m: its horizontal reach when it stopped growing
    double shrink = 0;          ///< scale about its base from the A-system's form to `reach`
    double longestPath = 0;     ///< m: from its base to its farthest tip, once scaled
    Vec3 base;
};

const StandTree& fellableTree(const Stand& stand, uint32_t treeId, const FellOptions& options) {
    if (treeId >= stand.trees.size())
        throw InputError("stand", "tree",
                         fmt::format("tree {} does not exist: the stand has trees 0..{}", treeId,
                                     stand.trees.size() - 1));
    const StandTree& tree = stand.trees[treeId];
    if (tree.history.empty())
        throw InputError("stand", "tree",
                         fmt::format("tree {} died in its first year: nothing to fell", treeId));
    if (!(options.minRingWidth > 0) || !std::isfinite(options.minRingWidth))
        throw InputError("fell options", "min_ring_width",
                         fmt::format("is {}: expected a width > 0 (m)", options.minRingWidth));
    return tree;
}

/// The trunk's top at the final height (one uniform scale keeps the A-system's angles).
void scaleToHeight(std::vector<ASystemAxis>& axes, double height) {
    double scale = height / axes[0].points.back().z;
    for (ASystemAxis& axis : axes)
        for (Vec3& p : axis.points) p = p * scale;
}

/// Per axis, the first-order axis whose limb it is part of (-1 for the trunk).
std::vector<int> limbOfAxes(const std::vector<ASystemAxis>& axes) {
    std::vector<int> limbOf(axes.size(), -1);
    for (size_t a = 1; a < axes.size(); ++a)
        limbOf[a] =
            axes[a].order == 1 ? static_cast<int>(a) : limbOf[static_cast<size_t>(axes[a].parent)];
    return limbOf;
}

/// The limbs (indexed by their first-order axis): timing and reach from the tree's life, and
/// in `shrink` the horizontal reach the A-system's form gives them.
std::vector<Limb> timeLimbs(const std::vector<ASystemAxis>& axes, const std::vector<int>& limbOf,
                            const Life& life) {
    const int age = life.years();
    const TreeYear& final = life.at(age);
    std::vector<Limb> limbs(axes.size());
    for (size_t a = 1; a < axes.size(); ++a) {
        const ASystemAxis& axis = axes[a];
        if (axis.order == 1) {
            Limb& l = limbs[a];
            l.base = axis.points[0];
            l.born = life.ageAtHeight(l.base.z);
            int died = life.ageCrownBasePassed(l.base.z);
            if (died >= 0) {
                l.stop = std::max<double>(died, l.born);
                l.death = l.stop;
                l.reach = life.at(died).crownRadius;
            } else {
                l.stop = age;
                double depth = std::max(final.height - final.crownBase, 1e-9);
                l.reach = final.crownRadius *
                          std::clamp((final.height - l.base.z) / depth, kTopReach, 1.0);
            }
        }
        Limb& l = limbs[static_cast<size_t>(limbOf[a])];
        for (const Vec3& p : axis.points)
            l.shrink = std::max(l.shrink, std::hypot(p.x - l.base.x, p.y - l.base.y));
    }
    // (shrink held the limb's horizontal reach in the form so far; now the scale factor)
    for (size_t a = 1; a < axes.size(); ++a)
        if (axes[a].order == 1)
            limbs[a].shrink = limbs[a].shrink > 0 ? limbs[a].reach / limbs[a].shrink : 1.0;
    return limbs;
}

/// Scales every limb about its base to its reach; returns per axis the path length of each
/// point from the limb's base (and sets the limbs' longest paths).
std::vector<std::vector<double>> shrinkLimbs(std::vector<ASystemAxis>& axes,
                                             const std::vector<int>& limbOf,
                                             std::vector<Limb>& limbs) {
    std::vector<std::vector<double>> path(axes.size());
    for (size_t a = 1; a < axes.size(); ++a) {
        ASystemAxis& axis = axes[a];
        const Limb& l = limbs[static_cast<size_t>(limbOf[a])];
        for (Vec3& p : axis.points) p = l.base + (p - l.base) * l.shrink;
        double s = axis.order == 1 ? 0.0
                                   : path[static_cast<size_t>(axis.parent)]
                                         [static_cast<size_t>(axis.parentSegment + 1)];
        path[a].push_back(s);
        for (size_t i = 1; i < axis.points.size(); ++i)
            path[a].push_back(path[a].back() + length(axis.points[i] - axis.points[i - 1]));
        Limb& lm = limbs[static_cast<size_t>(limbOf[a])];
        lm.longestPath = std::max(lm.longestPath, path[a].back());
    }
    return path;
}

void addTrunk(Skeleton& sk, const ASystemAxis& trunk, const Life& life) {
    const int age = life.years();
    std::vector<double> births, radii;
    for (const Vec3& p : trunk.points) {
        double born = life.ageAtHeight(p.z);
        births.push_back(born);
        // The stem at a node holds the rings laid since the leader passed it.
        radii.push_back(std::max(life.stemRadius(age) - life.stemRadius(born), 1e-3));
    }
    sk.addTrunk(trunk.points, births, radii);
}

/// Adds axis `a` of limb `l` as a branch: it grows at one speed along its paths (`path`) from
/// the limb's birth until it stops, and its wood is what the stem laid meanwhile, scaled by
/// gamma = widthRatio^order. Sets firstSegment[a].
void addLimbAxis(Skeleton& sk, const std::vector<ASystemAxis>& axes, size_t a, const Limb& l,
                 const std::vector<double>& path, const Life& life, double widthRatio,
                 std::vector<uint32_t>& firstSegment) {
    const ASystemAxis& axis = axes[a];
    std::vector<double> births, radii;
    double gamma = std::pow(widthRatio, axis.order);
    for (double s : path) {
        double born = l.longestPath > 0 ? l.born + (l.stop - l.born) * s / l.longestPath : l.born;
        births.push_back(born);
        radii.push_back(std::max(gamma * (life.stemRadius(l.stop) - life.stemRadius(born)), 5e-4));
    }
    ChainProperties props;
    props.gamma = gamma;
    props.deathTime = l.death;
    props.diebackExponent = 1;
    firstSegment[a] = static_cast<uint32_t>(sk.segments().size());
    sk.addBranch(
        firstSegment[static_cast<size_t>(axis.parent)] + static_cast<uint32_t>(axis.parentSegment),
        axis.points, births, props, radii);
}

}  // namespace

ASystemParams defaultFellForm() {
    ASystemParams p = aSystemPreset("aono-kunii-b");
    p.generations = 7;
    p.trunkForks = 20;
    return p;
}

std::vector<double> standTreeRingWidths(const StandTree& tree, double minRingWidth) {
    std::vector<double> widths;
    double previous = 0;
    for (const TreeYear& y : tree.history) {
        widths.push_back(std::max(y.stemRadius - previous, minRingWidth));
        previous = y.stemRadius;
    }
    return widths;
}

Skeleton fellStandTree(const Stand& stand, uint32_t treeId, const FellOptions& options) {
    const StandTree& tree = fellableTree(stand, treeId, options);
    Life life(tree);
    std::vector<ASystemAxis> axes = growASystem(options.form, options.trunkSway);
    scaleToHeight(axes, life.at(life.years()).height);

    // Each first-order lateral and everything on it forms one limb: born when the leader
    // passed its fork, dead when the crown base passed it. Its reach is what the crown had
    // at the time it stopped growing: a dead limb reaches the crown radius of the year it
    // died (it was then at the bottom of the cylindrical crown); a living one the final
    // radius, less towards the top where it is young (a cone over the live crown). The limb
    // is scaled about its base (a similarity: angles kept, branches stay on their parents)
    // and grows at one speed along its paths.
    std::vector<int> limbOf = limbOfAxes(axes);
    std::vector<Limb> limbs = timeLimbs(axes, limbOf, life);
    std::vector<std::vector<double>> path = shrinkLimbs(axes, limbOf, limbs);

    Skeleton sk;
    std::vector<uint32_t> firstSegment(axes.size());
    addTrunk(sk, axes[0], life);
    for (size_t a = 1; a < axes.size(); ++a)
        addLimbAxis(sk, axes, a, limbs[static_cast<size_t>(limbOf[a])], path[a], life,
                    options.form.widthRatio, firstSegment);
    sk.setRingWidths(standTreeRingWidths(tree, options.minRingWidth));
    return sk;
}

TreePick treePickFromName(const std::string& name) {
    if (name == "dominant") return TreePick::Dominant;
    if (name == "suppressed") return TreePick::Suppressed;
    throw InputError(
        "fell options", "pick",
        fmt::format("unknown tree pick \"{}\": expected dominant or suppressed", name));
}

std::vector<std::string> treePickNames() { return {"dominant", "suppressed"}; }

uint32_t pickStandTree(const Stand& stand, TreePick pick) {
    int best = -1;
    double bestScore = 0;
    for (const StandTree& t : stand.trees) {
        if (!t.alive() || t.history.empty()) continue;
        double score;
        if (pick == TreePick::Dominant) {
            score = t.last().height;
        } else {
            int n = static_cast<int>(t.history.size());
            if (n < kSuppressedMinAge) continue;
            double light = 0;
            for (int k = n - kSuppressedWindow; k < n; ++k) {
                double I0 = stand.irradiance[static_cast<size_t>(t.birthYear + k)];
                light += I0 > 0 ? t.history[static_cast<size_t>(k)].irradiance / I0 : 0;
            }
            score = -light;
        }
        if (best < 0 || score > bestScore) {
            best = static_cast<int>(t.id);
            bestScore = score;
        }
    }
    if (best < 0)
        throw InputError("stand", "pick",
                         pick == TreePick::Dominant
                             ? std::string("no living tree to pick")
                             : fmt::format("no living tree at least {} years old to pick as "
                                           "suppressed",
                                           kSuppressedMinAge));
    return static_cast<uint32_t>(best);
}

}  // namespace nenrin
