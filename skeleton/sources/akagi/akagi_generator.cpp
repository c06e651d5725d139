#include "skeleton/sources/akagi/akagi_generator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "util/input_error.h"
#include "util/random_draws.h"

namespace nenrin {

namespace {

constexpr double kRootGrowthElement = 100;  // paper 2.4 (1)
constexpr double kLeafThreshold = 1;        // paper 2.4 (2)
constexpr double kDegree = std::numbers::pi / 180;

// Working record of pass 1 (topology and growth elements) and pass 2 (geometry), unscaled.
struct Element {
    int32_t parent = kNone;
    int childIndex = 0;
    double g = 0;       // growth element
    double length = 0;  // unscaled
    double area = 0;    // pipe-model cross-section (m^2)
    int depth = 0;
    int leafClusters = 0;
    int32_t dominant = kNone;  // child the chain continues along
    std::vector<int32_t> children;
    Vec3 start, dir, ref, end;
};

// Rotates v about the unit axis by angle (Rodrigues).
Vec3 rotateAbout(const Vec3& v, const Vec3& axis, double angle) {
    double c = std::cos(angle), s = std::sin(angle);
    return v * c + cross(axis, v) * s + axis * (dot(axis, v) * (1 - c));
}

// Unit vector perpendicular to dir, as close to `hint` as possible.
Vec3 perpendicularTo(const Vec3& dir, const Vec3& hint) {
    Vec3 p = hint - dir * dot(hint, dir);
    return lengthSquared(p) > 1e-12 ? normalize(p) : anyPerpendicular(dir);
}

double segmentDistance(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
    Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
    double s = 0, t = 0;
    if (a <= 1e-300 && e <= 1e-300) return length(r);
    if (a <= 1e-300) {
        t = std::clamp(f / e, 0.0, 1.0);
    } else {
        double c = dot(d1, r);
        if (e <= 1e-300) {
            s = std::clamp(-c / a, 0.0, 1.0);
        } else {
            double b = dot(d1, d2), denom = a * e - b * b;
            s = denom > 1e-300 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
            t = (b * s + f) / e;
            if (t < 0) {
                t = 0;
                s = std::clamp(-c / a, 0.0, 1.0);
            } else if (t > 1) {
                t = 1;
                s = std::clamp((b - c) / a, 0.0, 1.0);
            }
        }
    }
    return length((p0 + d1 * s) - (q0 + d2 * t));
}

// Pass 1: who grows from whom, with which growth element (paper 2.4 (2), (4)).
std::vector<Element> growTopology(const AkagiParams& p, size_t maxSegments, double lengthExponent,
                                  bool& truncated) {
    std::vector<Element> elements(1);
    elements[0].g = kRootGrowthElement;
    elements[0].length = 1;  // paper 2.4 (1)
    int childCount = std::max(1, static_cast<int>(std::lround(p.branchNum)));
    // Shares of a branch point: the paper distributes the parent's growth element, so shares
    // summing above 1 are normalised (no growth element is created at a fork).
    double nominal = p.mainGrowth + (childCount - 1) * p.subGrowth;
    double norm = nominal > 1 ? 1 / nominal : 1;
    double mainShare = p.mainGrowth * norm, subShare = p.subGrowth * norm;
    truncated = false;
    for (size_t e = 0; e < elements.size(); ++e) {
        double g = elements[e].g;
        // GrowthGain (P13): shade over a lateral grows with the growth element still above it,
        // i.e. the crown this point carries: g / 100 is 1 at the base, ~0 at the tips.
        double suppression = std::exp(-p.growthGain * g / kRootGrowthElement);
        for (int k = 0; k < childCount; ++k) {
            double share = k == 0 ? mainShare : subShare * suppression;
            double childG = g * share;
            if (childG <= 0) continue;
            if (childG < kLeafThreshold) {
                ++elements[e].leafClusters;
                continue;
            }
            if (elements.size() >= maxSegments) {
                truncated = true;
                continue;
            }
            Element c;
            c.parent = static_cast<int32_t>(e);
            c.childIndex = k;
            c.g = childG;
            c.length = elements[e].length * std::pow(childG / g, lengthExponent);  // 2.4 (3)
            c.depth = elements[e].depth + 1;
            elements[e].children.push_back(static_cast<int32_t>(elements.size()));
            elements.push_back(std::move(c));
        }
        // The chain continues along the strongest child; ties go to the main axis (lower k).
        double best = -1;
        for (int32_t c : elements[e].children)
            if (elements[c].g > best * (1 + 1e-12)) {
                best = elements[c].g;
                elements[e].dominant = c;
            }
    }
    return elements;
}

// P11 BranchPoint: the first fork of every axis sits at that fraction of the axis length, so
// the axis' first segment is stretched (or shortened) accordingly.
void placeFirstForks(std::vector<Element>& el, double branchPoint) {
    for (size_t e = 0; e < el.size(); ++e) {
        bool axisStart = el[e].parent == kNone || el[el[e].parent].dominant != (int32_t)e;
        if (!axisStart) continue;
        double rest = 0;
        for (int32_t c = el[e].dominant; c != kNone; c = el[c].dominant) rest += el[c].length;
        if (rest <= 0) continue;
        double wanted = branchPoint / (1 - branchPoint) * rest;
        // Keep a short stub when BranchPoint ~ 0 so the segment has a length.
        // Only this segment changes: what grows from its end keeps its lengths and moves along.
        el[e].length = std::max(wanted, 0.02 * rest);
    }
}

// Pass 2: directions (paper 2.4 (6)), positions, pipe-model areas (paper 2.4 (5)).
void placeSegments(std::vector<Element>& el, const AkagiParams& p, double jitterDeg,
                   SplitMix& rng) {
    const Vec3 up{0, 0, 1};
    double azimuth = rng.uniform(0, 2 * std::numbers::pi);
    el[0].start = Vec3{};
    el[0].dir = up;
    el[0].ref = Vec3{std::cos(azimuth), std::sin(azimuth), 0};
    el[0].area = std::numbers::pi * p.radius * p.radius;
    el[0].end = el[0].dir * el[0].length;
    int childCount = std::max(1, static_cast<int>(std::lround(p.branchNum)));
    int laterals = childCount - 1;
    for (size_t e = 0; e < el.size(); ++e) {
        Element& parent = el[e];
        double jitter = jitterDeg * kDegree;
        // The branching plane turns by MainRotation at every fork (phyllotaxis).
        Vec3 plane = rotateAbout(parent.ref, parent.dir,
                                 p.mainRotation * kDegree + jitter * drawNormal(rng));
        double childGrowth = 0;
        for (int32_t c : parent.children) childGrowth += el[c].g;
        for (int32_t c : parent.children) {
            Element& child = el[c];
            Vec3 dir;
            double tiltJitter = jitter * drawNormal(rng);  // drawn for every child: fixed order
            if (child.childIndex == 0) {
                dir = rotateAbout(parent.dir, normalize(cross(parent.dir, plane)),
                                  p.mainAngle * kDegree);  // no jitter: see options
            } else {
                // Laterals spread evenly around the parent, opposite the main axis' lean.
                double around =
                    std::numbers::pi + 2 * std::numbers::pi * (child.childIndex - 1) / laterals;
                Vec3 toward = rotateAbout(plane, parent.dir, around);
                dir = rotateAbout(parent.dir, normalize(cross(parent.dir, toward)),
                                  p.subAngle * kDegree + tiltJitter);
                // P12 Horizontal pulls leaf-bearing laterals toward the horizontal plane.
                Vec3 flat = dir - up * (p.horizontal * dir.z);
                if (lengthSquared(flat) > 1e-12) dir = normalize(flat);
            }
            child.dir = normalize(dir);
            child.ref = perpendicularTo(child.dir, plane);
            child.start = parent.end;
            child.end = child.start + child.dir * child.length;
            child.area = parent.area * child.g / childGrowth;  // pipe model
        }
    }
}

Vec3 leafDirection(const Element& e, int i, int count) {
    Vec3 around = rotateAbout(e.ref, e.dir, 2 * std::numbers::pi * i / std::max(count, 1));
    return normalize(rotateAbout(e.dir, normalize(cross(e.dir, around)), 60 * kDegree));
}

double chainLength(const Skeleton& s, uint32_t c) {
    const SkeletonChain& chain = s.chain(c);
    double l = 0;
    for (uint32_t i = 0; i < chain.segmentCount; ++i) {
        const SkeletonSegment& seg = s.segment(chain.firstSegment + i);
        l += length(s.end(seg) - s.start(seg));
    }
    return l;
}

// Horizontal distance from the trunk chain at the point's height (the trunk's first segment
// spanning that height; its nearer end if none does).
double horizontalOffsetFromTrunk(const Skeleton& s, const Vec3& p) {
    const SkeletonChain& trunk = s.chain(0);
    Vec3 axis = s.node(0).position;
    double bestGap = std::numeric_limits<double>::infinity();
    for (uint32_t i = 0; i < trunk.segmentCount; ++i) {
        const SkeletonSegment& seg = s.segment(trunk.firstSegment + i);
        Vec3 a = s.start(seg), b = s.end(seg);
        double lo = std::min(a.z, b.z), hi = std::max(a.z, b.z);
        if (p.z >= lo && p.z <= hi && hi > lo) {
            axis = lerp(a, b, (p.z - a.z) / (b.z - a.z));
            break;
        }
        for (const Vec3& end : {a, b})
            if (std::abs(end.z - p.z) < bestGap) bestGap = std::abs(end.z - p.z), axis = end;
    }
    return std::hypot(p.x - axis.x, p.y - axis.y);
}

void checkGenerateInputs(const AkagiParams& params, double years,
                         const AkagiGenerateOptions& options) {
    validateAkagiParams(params, "Akagi parameters");
    if (!(std::isfinite(years) && years > 0))
        throw InputError("Akagi tree", "years",
                         "expected a number > 0, found " + std::to_string(years));
    if (!(std::isfinite(options.angleJitterDeg) && options.angleJitterDeg >= 0))
        throw InputError("Akagi tree", "angleJitterDeg", "expected a number >= 0");
    if (!(std::isfinite(options.lengthExponent) && options.lengthExponent > 0 &&
          options.lengthExponent <= 2))
        throw InputError("Akagi tree", "lengthExponent", "expected a number in (0, 2]");
    if (options.maxSegments < 1)
        throw InputError("Akagi tree", "maxSegments", "expected at least 1");
}

/// Paper 2.4 (8): scales the tree so that its highest point is at `height`; returns the scale.
double scaleToHeight(std::vector<Element>& el, double height) {
    double top = 0;
    for (const Element& e : el) top = std::max({top, e.start.z, e.end.z});
    double scale = top > 0 ? height / top : 1;
    for (Element& e : el) {
        e.start = e.start * scale;
        e.end = e.end * scale;
        e.length *= scale;
    }
    return scale;
}

/// Birth time from the growth element: log(100 / g) / log(100) runs from 0 at the root to 1
/// where the growth element reaches the leaf threshold, so every tip ends at `years` and the
/// wood low and inside the tree is the oldest.
struct BirthClock {
    const std::vector<Element>& el;
    double years;

    double timeOf(double g) const {
        return years * std::clamp(std::log(kRootGrowthElement / g) / std::log(kRootGrowthElement),
                                  0.0, 1.0);
    }
    /// When the tip left the element's end: when its dominant child was born.
    double endTime(const Element& e) const {
        return e.dominant == kNone ? years : timeOf(el[e.dominant].g);
    }
};

struct Chains {
    std::vector<std::vector<int32_t>> members;    ///< per chain, its elements from the base
    std::vector<uint32_t> chainOf, indexInChain;  ///< per element
};

/// Chains: from each axis start follow the dominant child. Depth-first pre-order (a chain,
/// then the branches along it from base to tip, each with its own branches), so a parent
/// chain comes before its branches and the order is the one a skeleton file nests them in.
Chains collectChains(const std::vector<Element>& el) {
    Chains chains;
    std::vector<int32_t> starts{0};
    while (!starts.empty()) {
        int32_t s = starts.back();
        starts.pop_back();
        std::vector<int32_t> chain;
        for (int32_t e = s; e != kNone; e = el[e].dominant) chain.push_back(e);
        std::vector<int32_t> branches;
        for (int32_t e : chain)
            for (int32_t c : el[e].children)
                if (c != el[e].dominant) branches.push_back(c);
        starts.insert(starts.end(), branches.rbegin(), branches.rend());
        chains.members.push_back(std::move(chain));
    }
    chains.chainOf.resize(el.size());
    chains.indexInChain.resize(el.size());
    for (size_t c = 0; c < chains.members.size(); ++c)
        for (size_t i = 0; i < chains.members[c].size(); ++i) {
            chains.chainOf[chains.members[c][i]] = static_cast<uint32_t>(c);
            chains.indexInChain[chains.members[c][i]] = static_cast<uint32_t>(i);
        }
    return chains;
}

/// Adds chain `c` to the skeleton: the trunk for chain 0, else a branch on the segment of its
/// parent chain it grows from. `trunkSpeed` is the trunk's mean radial speed (m/year).
void addChain(AkagiTree& tree, const std::vector<Element>& el, const Chains& chains, size_t c,
              const BirthClock& clock, double trunkSpeed) {
    const std::vector<int32_t>& chain = chains.members[c];
    const Element& first = el[chain[0]];
    double startTime = first.parent == kNone ? 0.0 : clock.endTime(el[first.parent]);
    std::vector<Vec3> points{first.start};
    std::vector<double> times{startTime};
    std::vector<double> radii{std::sqrt(first.area / std::numbers::pi)};
    for (size_t i = 0; i < chain.size(); ++i) {
        const Element& e = el[chain[i]];
        points.push_back(e.end);
        times.push_back(std::max(clock.endTime(e), times.back()));
        int32_t next = e.dominant;
        radii.push_back(std::sqrt((next == kNone ? e.area : el[next].area) / std::numbers::pi));
    }
    if (c == 0) {
        tree.skeleton.addTrunk(points, times, radii);
        return;
    }
    // gamma: the branch's mean radial speed (base radius over its age) relative to the
    // trunk's (Radius over the tree's age).
    double years = clock.years;
    double age = std::max(years - startTime, 1e-3 * years);
    ChainProperties props;
    props.gamma = std::clamp(radii[0] / age / trunkSpeed, 0.02, 1.0);
    props.diebackExponent = 1;
    uint32_t parentChain = chains.chainOf[first.parent];
    uint32_t parentSegment =
        tree.skeleton.chain(parentChain).firstSegment + chains.indexInChain[first.parent];
    tree.skeleton.addBranch(parentSegment, points, times, props, radii);
}

/// The public segment records, and the leaves at the segments' tips.
void recordSegments(AkagiTree& tree, const std::vector<Element>& el, const Chains& chains,
                    const BirthClock& clock) {
    tree.segments.resize(el.size());
    for (size_t i = 0; i < el.size(); ++i) {
        const Element& e = el[i];
        AkagiSegment& s = tree.segments[i];
        s.parent = e.parent;
        s.childIndex = e.childIndex;
        s.growthElement = e.g;
        s.start = e.start;
        s.end = e.end;
        s.radius = std::sqrt(e.area / std::numbers::pi);
        s.birthTime = e.parent == kNone ? 0.0 : clock.endTime(el[e.parent]);
        s.chain = chains.chainOf[i];
        s.skeletonSegment =
            tree.skeleton.chain(chains.chainOf[i]).firstSegment + chains.indexInChain[i];
        s.children = e.children;
        tree.stats.maxDepth = std::max(tree.stats.maxDepth, e.depth);
        int perCluster = static_cast<int>(std::lround(tree.params.leafNum));
        for (int k = 0; k < e.leafClusters * perCluster; ++k)
            tree.leaves.push_back({e.end, leafDirection(e, k, perCluster), tree.params.leafSize});
    }
}

/// Path length from the root along the main-axis children (child 0) only.
double mainAxisLength(const std::vector<Element>& el) {
    double total = 0;
    for (int32_t e = 0; e != kNone;) {
        total += el[e].length;
        int32_t next = kNone;
        for (int32_t c : el[e].children)
            if (el[c].childIndex == 0) next = c;
        e = next;
    }
    return total;
}

/// The tree's summary numbers (what isPlausible checks and the CLI reports).
void measureTree(AkagiTree& tree, const std::vector<Element>& el, size_t chainCount, double scale) {
    AkagiTreeStats& st = tree.stats;
    st.segmentCount = el.size();
    st.leafCount = tree.leaves.size();
    st.chainCount = chainCount;
    st.scale = scale;
    double xlo = 0, xhi = 0, ylo = 0, yhi = 0, zlo = 0, zhi = 0, farthest = -1;
    for (const SkeletonNode& n : tree.skeleton.nodes()) {
        double off = horizontalOffsetFromTrunk(tree.skeleton, n.position);
        if (off > farthest) {
            farthest = off;
            st.widestRelativeHeight = n.position.z / tree.params.height;
        }
        xlo = std::min(xlo, n.position.x), xhi = std::max(xhi, n.position.x);
        ylo = std::min(ylo, n.position.y), yhi = std::max(yhi, n.position.y);
        zlo = std::min(zlo, n.position.z), zhi = std::max(zhi, n.position.z);
    }
    st.height = zhi;
    st.lowestZ = zlo;
    st.crownWidth = std::max(xhi - xlo, yhi - ylo);
    st.trunkLength = chainLength(tree.skeleton, 0);
    const SkeletonChain& trunk = tree.skeleton.chain(0);
    Vec3 trunkTop =
        tree.skeleton.end(tree.skeleton.segment(trunk.firstSegment + trunk.segmentCount - 1));
    st.trunkTopZ = trunkTop.z;
    st.trunkStraightness = st.trunkLength > 0 ? length(trunkTop) / st.trunkLength : 0;
    st.mainAxisLength = mainAxisLength(el);
    for (uint32_t c = 1; c < tree.skeleton.chains().size(); ++c)
        st.longestBranchLength = std::max(st.longestBranchLength, chainLength(tree.skeleton, c));
    st.firstForkHeight = el[0].end.z;
}

}  // namespace

AkagiTree generateAkagiTree(const AkagiParams& params, uint64_t seed, double years,
                            const AkagiGenerateOptions& options) {
    checkGenerateInputs(params, years, options);
    AkagiTree tree;
    tree.params = params;
    tree.years = years;
    SplitMix rng(hashCombine(seed, 0xa6a91ull));
    std::vector<Element> el =
        growTopology(params, options.maxSegments, options.lengthExponent, tree.stats.truncated);
    placeFirstForks(el, params.branchPoint);
    placeSegments(el, params, options.angleJitterDeg, rng);
    double scale = scaleToHeight(el, params.height);

    const BirthClock clock{el, years};
    Chains chains = collectChains(el);
    double trunkSpeed = params.radius / years;
    for (size_t c = 0; c < chains.members.size(); ++c)
        addChain(tree, el, chains, c, clock, trunkSpeed);
    recordSegments(tree, el, chains, clock);
    measureTree(tree, el, chains.members.size(), scale);
    return tree;
}

bool isPlausible(const AkagiTree& tree, std::string* why) {
    auto fail = [&](const std::string& reason) {
        if (why) *why = reason;
        return false;
    };
    const AkagiTreeStats& st = tree.stats;
    const AkagiParams& p = tree.params;
    if (st.truncated) return fail("the segment budget ran out");
    if (st.segmentCount < 8) return fail("fewer than 8 segments: no crown");
    if (st.lowestZ < -1e-9 * p.height) return fail("a segment reaches below ground");
    double ratio = st.crownWidth / p.height;
    if (ratio < 0.1 || ratio > 2.0)
        return fail("crown width / height = " + std::to_string(ratio) + " outside [0.1, 2]");
    if (st.leafCount < 20 || st.leafCount > 200000)
        return fail("leaf count " + std::to_string(st.leafCount) + " outside [20, 200000]");
    if (st.trunkTopZ < 0.4 * p.height) return fail("the trunk ends below 0.4 Height");
    double slenderness = p.height / (2 * p.radius);
    if (slenderness < 5 || slenderness > 250)
        return fail("Height / trunk diameter = " + std::to_string(slenderness) +
                    " outside [5, 250]");
    // Main axes must not fold back onto themselves.
    const Skeleton& s = tree.skeleton;
    double clearance = 0.002 * p.height;
    for (uint32_t c = 0; c < s.chains().size(); ++c) {
        const SkeletonChain& chain = s.chain(c);
        if (chain.order > 1) continue;
        for (uint32_t i = 0; i < chain.segmentCount; ++i)
            for (uint32_t j = i + 2; j < chain.segmentCount; ++j) {
                const SkeletonSegment& a = s.segment(chain.firstSegment + i);
                const SkeletonSegment& b = s.segment(chain.firstSegment + j);
                if (segmentDistance(s.start(a), s.end(a), s.start(b), s.end(b)) < clearance)
                    return fail("main axis (chain " + std::to_string(c) + ") crosses itself");
            }
    }
    if (why) why->clear();
    return true;
}

}  // namespace nenrin
