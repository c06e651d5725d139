#include "skeleton/sources/hayashi/hayashi_conifer.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "skeleton/sources/hayashi/crown_profile.h"
#include "skeleton/sources/hayashi/rodrigues_rotation.h"
#include "skeleton/sources/hayashi/seasonal_height_growth.h"
#include "skeleton/sources/hayashi/truncated_normal.h"
#include "util/hash.h"
#include "util/random_draws.h"

namespace nenrin {

namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;
/// Side branches that would be shorter than this at the end are left out.
constexpr double kMinBranchLength = 5e-4;
/// Trunk heights closer than this share one node.
constexpr double kMergeHeight = 2e-6;
/// A node just above each year's top carries the winter pause: the point at the top was
/// reached at the end of the season, the point above only next spring.
constexpr double kWinterStep = 1e-3;
/// Extra trunk nodes at most this far apart (birth time is nonlinear in height).
constexpr double kTrunkGrid = 0.25;
/// A multiplicative scatter about 1 with relative sd `v` (0: none), cut at 2.5 sd and at 0.1.
double scatterFactor(SplitMix& rng, double v) {
    return v > 0 ? drawTruncatedNormal(rng, 1, v, std::max(0.1, 1 - 2.5 * v), 1 + 2.5 * v) : 1.0;
}

constexpr double kTrunkTipRadius = 0.002;
constexpr double kBranchTipRadius = 0.0005;

/// Seeds of the independent random streams: one per purpose, one per first-order branch,
/// one per side branch (keyed by its parent's key and its index). Changing max_order or a
/// side-branch option never moves the trunk or the first-order branches.
enum Stream : uint64_t { kTrunkStream = 1, kArrangementStream = 2, kBranchStream = 3 };

struct ParentChain {
    uint32_t firstSegment;
    Vec3 origin, direction;
    double length;
    std::vector<double> s, times;  ///< node distances along the chain and their birth times
    double gamma, endTime, deathTime;
    uint64_t key;
};

class Generator {
public:
    Generator(const HayashiOptions& o, HayashiTree& tree) : o_(o), tree_(tree) {}

    void run();

private:
    void growTrunkHeights();
    void placeSpiral();
    void placeWhorls();
    void buildTrunk();
    void addFirstOrder(HayashiBranchRecord& r, uint32_t parentSegment, size_t index);
    void addSideBranches(const ParentChain& parent, int order);
    const SubBranchOrder& sub(int order) const {
        return order == 2 ? o_.second : (order == 3 ? o_.third : o_.fourth);
    }
    void count(int order, size_t segments) {
        tree_.chainsPerOrder[order] += 1;
        tree_.segmentsPerOrder[order] += segments;
    }

    const HayashiOptions& o_;
    HayashiTree& tree_;
    SeasonalHeightGrowth clock_{{0, 1}, 1, 1};
    std::vector<double> trunkHeights_;
    std::vector<Vec3> pts_;
    std::vector<double> times_, radii_;
};

void Generator::growTrunkHeights() {
    SplitMix rng(hashCombine(o_.seed, kTrunkStream));
    std::vector<double> h{0};
    for (int y = 0; y < o_.years; ++y) {
        h.push_back(h.back() + o_.heightGrowth * scatterFactor(rng, o_.heightGrowthVariation));
    }
    clock_ = SeasonalHeightGrowth(h, o_.growingSeason, o_.seasonShape);
    tree_.yearStartHeights = h;
    tree_.height = h.back();
    tree_.crownBase = (1 - o_.crownRatio) * tree_.height;
}

void Generator::placeSpiral() {
    SplitMix rng(hashCombine(o_.seed, kArrangementStream));
    TruncatedNormal divergence = TruncatedNormal::fromMoments(o_.divergenceMean(), o_.divergenceSd,
                                                              o_.divergenceMin, o_.divergenceMax);
    double perYear = kTwoPi * o_.turnsPerYear;  // spiral rotation laid down per growing season
    double azimuth0 = rng.uniform(0, kTwoPi);
    // A random phase: the first branch sits somewhere within one divergence of the start.
    double c = rng.uniform(0, o_.divergenceMean());
    double first = c;
    for (;;) {
        double yf = std::floor(c / perYear);
        if (yf >= o_.years) break;
        int y = static_cast<int>(yf);
        // Rotation runs evenly through the season; height growth is front-loaded (Fig. 9).
        double u = c / perYear - yf;
        HayashiBranchRecord r;
        r.year = y;
        r.birthTime = y + o_.growingSeason * u;
        r.height = clock_.heightAt(r.birthTime);
        r.spiralAngle = c - first;
        double az = azimuth0 + (o_.clockwise ? -c : c);
        r.azimuth = az - kTwoPi * std::floor(az / kTwoPi);
        // (A branch within a few micrometres of the ground would have no trunk segment below it.)
        if (r.height > 1e-4) tree_.firstOrder.push_back(r);
        c += divergence.draw(rng);
    }
}

void Generator::placeWhorls() {
    SplitMix rng(hashCombine(o_.seed, kArrangementStream));
    // The whorl at the top of year y's shoot breaks bud at the start of year y + 1.
    for (int y = 0; y + 1 < o_.years; ++y) {
        int n = o_.whorlMin + static_cast<int>(rng.uniform() * (o_.whorlMax - o_.whorlMin + 1));
        n = std::min(n, o_.whorlMax);
        double offset = rng.uniform(0, kTwoPi);
        for (int j = 0; j < n; ++j) {
            HayashiBranchRecord r;
            r.year = y + 1;
            r.whorl = y;
            r.birthTime = y + 1;
            r.height = tree_.yearStartHeights[y + 1];
            double az = offset + kTwoPi * j / n + o_.whorlJitter * drawNormal(rng);
            r.azimuth = az - kTwoPi * std::floor(az / kTwoPi);
            tree_.firstOrder.push_back(r);
        }
    }
}

void Generator::buildTrunk() {
    struct Mark {
        double h;
        bool branch;
    };
    std::vector<Mark> marks{{0, false}};
    for (const auto& r : tree_.firstOrder) marks.push_back({r.height, true});
    const auto& hs = tree_.yearStartHeights;
    for (size_t y = 1; y < hs.size(); ++y) {
        marks.push_back({hs[y], false});
        if (y + 1 < hs.size())
            marks.push_back({hs[y] + std::min(kWinterStep, 0.5 * (hs[y + 1] - hs[y])), false});
    }
    for (double h = kTrunkGrid; h < tree_.height; h += kTrunkGrid) marks.push_back({h, false});
    std::sort(marks.begin(), marks.end(), [](const Mark& a, const Mark& b) { return a.h < b.h; });
    // Merge near-equal heights; a branch's own height wins so its start is exactly a node.
    trunkHeights_.clear();
    std::vector<bool> isBranch;
    for (const auto& m : marks) {
        if (!trunkHeights_.empty() && m.h - trunkHeights_.back() < kMergeHeight) {
            if (m.branch && !isBranch.back() && trunkHeights_.size() > 1) {
                trunkHeights_.back() = m.h;
                isBranch.back() = true;
            }
            continue;
        }
        trunkHeights_.push_back(m.h);
        isBranch.push_back(m.branch);
    }
    pts_.clear();
    times_.clear();
    radii_.clear();
    for (double h : trunkHeights_) {
        double t = clock_.timeAt(h);
        pts_.push_back({0, 0, h});
        times_.push_back(t);
        radii_.push_back(kTrunkTipRadius + o_.ringWidth * std::max(0.0, o_.years - t));
    }
    tree_.skeleton.addTrunk(pts_, times_, radii_);
    count(0, pts_.size() - 1);
}

void Generator::addFirstOrder(HayashiBranchRecord& r, uint32_t parentSegment, size_t index) {
    uint64_t key = hashCombine(hashCombine(o_.seed, kBranchStream), index);
    SplitMix rng(key);
    double a = o_.crownCoefficient * scatterFactor(rng, o_.branchLengthVariation);
    double elLo = std::max(-89 * HayashiOptions::kDegree, o_.elevation - 2.5 * o_.elevationSd);
    double elHi = std::min(89 * HayashiOptions::kDegree, o_.elevation + 2.5 * o_.elevationSd);
    r.elevation = o_.elevationSd > 0
                      ? drawTruncatedNormal(rng, o_.elevation, o_.elevationSd, elLo, elHi)
                      : o_.elevation;
    r.gamma = o_.gamma * rng.uniform(1 - o_.gammaVariation, 1 + o_.gammaVariation);

    // The crown base rises with the tree: the branch dies when it falls out of the live crown,
    // and stops lengthening then.
    double deathHeight = o_.crownRatio < 1 ? r.height / (1 - o_.crownRatio) : kNeverDies;
    r.deathTime = deathHeight < tree_.height ? clock_.timeAt(deathHeight) : kNeverDies;
    double endHeight = std::min(deathHeight, tree_.height);
    double endTime = std::min<double>(r.deathTime, o_.years);
    r.length = crownBranchLength(a, endHeight, r.height);
    if (r.length < kMinBranchLength) return;

    Vec3 dir{std::cos(r.elevation) * std::cos(r.azimuth),
             std::cos(r.elevation) * std::sin(r.azimuth), std::sin(r.elevation)};
    Vec3 origin{0, 0, r.height};
    // Nodes where the second-order branches sit; the tip passed each when the tree was tall
    // enough for eq. 2 to reach it.
    ParentChain parent{0, origin, dir, r.length, {}, {}, r.gamma, endTime, r.deathTime, key};
    double spacing = o_.second.spacing;
    for (int k = 0;; ++k) {
        double s = k * spacing;
        if (k > 0 && s > r.length - 1e-4) s = r.length;
        double t = k == 0 ? r.birthTime
                          : std::max(r.birthTime,
                                     clock_.timeAt(treeHeightForBranchLength(a, r.height, s)));
        parent.s.push_back(s);
        parent.times.push_back(std::min(t, endTime));
        if (s == r.length) break;
    }
    pts_.clear();
    times_.clear();
    radii_.clear();
    for (size_t i = 0; i < parent.s.size(); ++i) {
        pts_.push_back(origin + dir * parent.s[i]);
        times_.push_back(parent.times[i]);
        radii_.push_back(kBranchTipRadius + r.gamma * o_.ringWidth * (endTime - parent.times[i]));
    }
    ChainProperties props{r.gamma, r.deathTime, 1.0};
    r.chain =
        static_cast<int32_t>(tree_.skeleton.addBranch(parentSegment, pts_, times_, props, radii_));
    parent.firstSegment = tree_.skeleton.chain(r.chain).firstSegment;
    count(1, pts_.size() - 1);
    if (o_.maxOrder >= 2) addSideBranches(parent, 2);
}

void Generator::addSideBranches(const ParentChain& parent, int order) {
    const SubBranchOrder& so = sub(order);
    double gamma = parent.gamma * o_.gammaOrderRatio;
    size_t seg = 0;
    for (int j = 1;; ++j) {
        double s = j * so.spacing;
        if (s >= parent.length) break;
        while (seg + 2 < parent.s.size() && parent.s[seg + 1] < s) ++seg;
        // Birth time at s: linear within the parent's segment (exact: side branches of a
        // first-order branch sit on its nodes, higher parents grow at a constant speed).
        double s0 = parent.s[seg], s1 = parent.s[seg + 1];
        double f = std::clamp((s - s0) / (s1 - s0), 0.0, 1.0);
        double birth = f >= 1 ? parent.times[seg + 1]
                              : parent.times[seg] + f * (parent.times[seg + 1] - parent.times[seg]);
        if (birth >= parent.endTime) break;
        double full = so.parabolic ? so.maxLength * std::sqrt(std::max(0.0, 1 - s / parent.length))
                                   : so.maxLength;
        double len = std::min(full, so.speed * (parent.endTime - birth));
        if (len < kMinBranchLength) continue;
        uint64_t key = hashCombine(parent.key, static_cast<uint64_t>(j));
        SplitMix rng(key);
        double beta = rng.uniform(0, kTwoPi);
        Vec3 dir = sideBranchDirection(parent.direction, o_.elongationAngle, beta);
        Vec3 start = parent.origin + parent.direction * s;
        double tipTime = birth + len / so.speed;
        pts_.assign({start, start + dir * len});
        times_.assign({birth, tipTime});
        radii_.assign(
            {kBranchTipRadius + gamma * o_.ringWidth * (parent.endTime - birth), kBranchTipRadius});
        ChainProperties props{gamma, parent.deathTime, 1.0};
        uint32_t chain = tree_.skeleton.addBranch(parent.firstSegment + static_cast<uint32_t>(seg),
                                                  pts_, times_, props, radii_);
        count(order, 1);
        if (order < o_.maxOrder) {
            ParentChain child{tree_.skeleton.chain(chain).firstSegment,
                              start,
                              dir,
                              len,
                              {0, len},
                              {birth, tipTime},
                              gamma,
                              parent.endTime,
                              parent.deathTime,
                              key};
            addSideBranches(child, order + 1);
        }
    }
}

void Generator::run() {
    growTrunkHeights();
    if (o_.arrangement == BranchArrangement::Spiral)
        placeSpiral();
    else
        placeWhorls();
    buildTrunk();
    // Branch starts are trunk nodes: find each one's node and start on the segment ending there.
    tree_.branchesPerYear.assign(o_.years, 0);
    for (size_t i = 0; i < tree_.firstOrder.size(); ++i) {
        auto& r = tree_.firstOrder[i];
        auto it =
            std::lower_bound(trunkHeights_.begin(), trunkHeights_.end(), r.height - kMergeHeight);
        size_t node = std::max<size_t>(1, static_cast<size_t>(it - trunkHeights_.begin()));
        r.height = trunkHeights_[node];
        // The trunk reached the node no later than the branch left it (the same moment on a
        // spiral; a winter earlier for a whorl).
        r.birthTime =
            std::max(r.birthTime, tree_.skeleton.node(static_cast<uint32_t>(node)).birthTime);
        tree_.branchesPerYear[std::min(r.year, o_.years - 1)] += 1;
        addFirstOrder(r, static_cast<uint32_t>(node - 1), i);
    }
}

}  // namespace

HayashiTree growHayashiConifer(const HayashiOptions& options) {
    validateHayashiOptions(options);
    HayashiTree tree;
    Generator(options, tree).run();
    return tree;
}

}  // namespace nenrin
