#include "grain/chain_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace nenrin {

namespace {

/// Segments per leaf: their exact distances cost about what the capsule tests of a descent do.
constexpr uint32_t kLeafSize = 4;

/// Squared distance from p to the axis of a capsule.
inline double axisDistance2(const Vec3& a, const Vec3& ab, double invLength2, const Vec3& p) {
    const Vec3 q = p - a;
    const double t = std::min(std::max(dot(q, ab) * invLength2, 0.0), 1.0);  // = std::clamp
    const Vec3 d = q - ab * t;
    return dot(d, d);
}

bool better(double e, uint32_t s, const ChainTrees::Nearest& best) {
    return e < best.distance2 || (e == best.distance2 && (best.segment == kNone ||
                                                          static_cast<int32_t>(s) < best.segment));
}

}  // namespace

ChainTrees::ChainTrees(std::span<const FieldSegment> segments,
                       std::span<const SkeletonChain> chains, bool hierarchical)
    : segments_(segments), hierarchical_(hierarchical) {
    for (const SkeletonChain& c : chains) {
        chainFirst_.push_back(c.firstSegment);
        chainEnd_.push_back(c.firstSegment + c.segmentCount);
        roots_.push_back(
            hierarchical && c.segmentCount > 0 ? build(c.firstSegment, chainEnd_.back()) : 0);
    }
}

uint32_t ChainTrees::build(uint32_t first, uint32_t last) {
    const uint32_t index = static_cast<uint32_t>(nodes_.size());
    nodes_.push_back({});
    Node n{};
    n.a = segments_[first].a;
    n.ab = segments_[last - 1].a + segments_[last - 1].ab - n.a;
    const double length2 = dot(n.ab, n.ab);
    n.invLength2 = length2 > 0 ? 1 / length2 : 0;
    // Every joint lies within `radius` of the axis, so (the capsule being convex) every
    // segment does. Rounded up by far more than the rounding of any distance here (~1e-14 m at
    // tree coordinates), so a segment tied with the best is never pruned.
    double radius2 = 0;
    for (uint32_t s = first; s < last; ++s)
        for (const Vec3& q : {segments_[s].a, segments_[s].a + segments_[s].ab})
            radius2 = std::max(radius2, axisDistance2(n.a, n.ab, n.invLength2, q));
    n.radius = std::sqrt(radius2) * (1 + 1e-9) + 1e-9;
    n.length = std::sqrt(length2);
    n.axis = length2 > 0 ? n.ab * (1 / n.length) : Vec3{};
    n.sinSpread = 1;
    if (length2 > 0) {
        // A run holding the chain's first or last segment has no bound: beyond the chain's
        // ends the nearest point is the end itself, seen from any direction.
        double cosMin = 1;
        auto widen = [&](int32_t s) {
            cosMin = s == kNone
                         ? -1
                         : std::min(cosMin, dot(segments_[static_cast<uint32_t>(s)].axis, n.axis));
        };
        for (uint32_t s = first; s < last; ++s) widen(static_cast<int32_t>(s));
        widen(segments_[first].previous);
        widen(segments_[last - 1].next);
        if (cosMin > 0)
            n.sinSpread = std::min(1.0, std::sqrt(1 - cosMin * cosMin) * (1 + 1e-9) + 1e-9);
    }
    n.first = first;
    n.last = last;
    if (last - first > kLeafSize) {  // depth is log2 of the chain's length: recursion is safe
        const uint32_t mid = first + (last - first) / 2;
        n.left = build(first, mid);
        n.right = build(mid, last);
    }
    nodes_[index] = n;
    return index;
}

ChainTrees::Nearest ChainTrees::nearest(uint32_t chain, const Vec3& p, double maxDistance2) const {
    if (!hierarchical_) return nearestByScan(chain, p, maxDistance2);
    return search(chain, p, maxDistance2);
}

ChainTrees::BoxQuery ChainTrees::makeBoxQuery(const Vec3& centre, const Vec3& half,
                                              double farthest) {
    BoxQuery q;
    q.centre = centre;
    q.half = half;
    q.farthest = farthest;
    const double keep = (q.farthest + length(q.half)) * (1 + 1e-9) + 1e-9;
    q.keep2 = keep * keep;
    // A segment whose joint J could be a point's nearest point lies within `farthest` of it:
    // |P - J| = q <= farthest. The two squared distances round to within ~1e-15 (q^2 + q M),
    // M the largest coordinate; the neighbour is nearer by at least along^2. Ask for 1000x.
    const double m = std::max({std::abs(centre.x), std::abs(centre.y), std::abs(centre.z)}) +
                     length(half) + farthest;
    q.jointMargin = std::sqrt(1e-12 * farthest * (2 * farthest + m));
    return q;
}

ChainTrees::BoxQuery ChainTrees::boxQuery(const Vec3& lo, const Vec3& hi,
                                          uint32_t nearestToCentre) const {
    // Distance to a segment is convex in P, so over the box the distance to the centre's
    // nearest segment is largest at a corner: no point of the box has its nearest farther
    // than that, and no candidate lies farther than that plus the half-diagonal from the centre.
    double farthest2 = 0;
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 c{corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z};
        farthest2 = std::max(farthest2, project(segments_[nearestToCentre], c).distance2);
    }
    return makeBoxQuery((lo + hi) * 0.5, (hi - lo) * 0.5, std::sqrt(farthest2) * (1 + 1e-9) + 1e-9);
}

inline bool ChainTrees::mayBeNearest(uint32_t segmentId, const BoxQuery& box) const {
    // tRaw is linear in P: over the box it spans its centre value +- a half-width. The nearest
    // point of a chain to P is inside a segment (P in its slab, 0 <= tRaw <= 1) or a joint; at
    // the joint ending segment s, tRaw_s >= 1 and the next segment's tRaw <= 0 (else a point
    // inside one of them would be nearer), and the same at its start. Margins cover rounding.
    auto range = [&](const FieldSegment& x) {
        double mid = dot(box.centre - x.a, x.ab) * x.invLength2;
        double spread = (std::abs(x.ab.x) * box.half.x + std::abs(x.ab.y) * box.half.y +
                         std::abs(x.ab.z) * box.half.z) *
                        x.invLength2;
        spread = spread * (1 + 1e-9) + 1e-9;
        return std::pair{mid - spread, mid + spread};
    };
    const FieldSegment& s = segments_[segmentId];
    const auto [mn, mx] = range(s);
    if (mx >= 0 && mn <= 1) return true;  // the box meets the slab
    if (mn > 1) {  // wholly past the end: the wedge before the next segment's start plane
        if (s.next == kNone) return true;
        const FieldSegment& next = segments_[static_cast<uint32_t>(s.next)];
        return range(next).first <= box.jointMargin / next.length;
    }
    // wholly before the start: the wedge past the previous segment's end plane
    if (s.previous == kNone) return true;
    const FieldSegment& previous = segments_[static_cast<uint32_t>(s.previous)];
    return range(previous).second >= 1 - box.jointMargin / previous.length;
}

double ChainTrees::candidates(uint32_t chain, const Vec3& lo, const Vec3& hi,
                              uint32_t nearestToCentre, std::vector<uint32_t>& out) const {
    if (!hierarchical_) return candidatesByScan(chain, lo, hi, nearestToCentre, out);
    const BoxQuery box = boxQuery(lo, hi, nearestToCentre);
    if (chainFirst_[chain] == chainEnd_[chain]) return box.farthest;
    const double keep = std::sqrt(box.keep2);
    uint32_t stack[64];  // left child on top: segments come out in id order
    int top = 0;
    stack[top++] = roots_[chain];
    while (top > 0) {
        const Node& n = nodes_[stack[--top]];
        // Too far from the centre.
        const double reach = keep + n.radius;
        if (axisDistance2(n.a, n.ab, n.invLength2, box.centre) > reach * reach * (1 + 1e-9))
            continue;
        // No point of the box projects onto the run: for P and its nearest point X on a
        // segment of the run (or the joint at one of its ends), P - X is perpendicular to a
        // direction within the run's spread of the axis, so P's position along the axis is
        // within |P - X| sin(spread) <= farthest sin(spread) of X's, which lies within the
        // capsule's radius of [0, length].
        if (n.length > 0) {
            const double along = dot(box.centre - n.a, n.axis);
            const double extent = std::abs(n.axis.x) * box.half.x +
                                  std::abs(n.axis.y) * box.half.y + std::abs(n.axis.z) * box.half.z;
            const double slack = (n.radius + box.farthest * n.sinSpread) * (1 + 1e-9) + 1e-9;
            if (along + extent < -slack || along - extent > n.length + slack) continue;
        }
        if (n.left == 0) {
            for (uint32_t s = n.first; s < n.last; ++s)
                if (project(segments_[s], box.centre).distance2 <= box.keep2 &&
                    mayBeNearest(s, box))
                    out.push_back(s);
            continue;
        }
        stack[top++] = n.right;
        stack[top++] = n.left;
    }
    return box.farthest;
}

void ChainTrees::narrow(std::span<const uint32_t> segments, const Vec3& lo, const Vec3& hi,
                        double farthest, std::vector<uint32_t>& out) const {
    const BoxQuery box = makeBoxQuery((lo + hi) * 0.5, (hi - lo) * 0.5, farthest);
    for (const uint32_t s : segments)
        if (mayBeNearest(s, box)) out.push_back(s);
}

ChainTrees::Nearest ChainTrees::search(uint32_t chain, const Vec3& p, double maxDistance2) const {
    if (chainFirst_[chain] == chainEnd_[chain]) return {};
    // A chain of one leaf (most of a simulated conifer's twigs): its segments cost less than
    // the capsule around them.
    if (nodes_[roots_[chain]].left == 0) return nearestByScan(chain, p, maxDistance2);
    Nearest best{kNone, maxDistance2};
    double bestDistance = std::sqrt(best.distance2);
    // A node can hold a segment within the best distance only if its axis is within that plus
    // its radius (relative margin: the rounding of the square and the square root).
    auto prunable = [&](double axis2, const Node& n) {
        const double reach = bestDistance + n.radius;
        return axis2 > reach * reach * (1 + 1e-9);
    };
    struct Entry {
        uint32_t node;
        double axis2;
    };
    Entry stack[96];  // depth-first, nearer child first: at most two entries per level
    int top = 0;
    const uint32_t root = roots_[chain];
    stack[top++] = {root,
                    axisDistance2(nodes_[root].a, nodes_[root].ab, nodes_[root].invLength2, p)};
    while (top > 0) {
        const Entry e = stack[--top];
        const Node& n = nodes_[e.node];
        if (prunable(e.axis2, n)) continue;
        if (n.left == 0) {
            for (uint32_t s = n.first; s < n.last; ++s) {
                const double d2 = project(segments_[s], p).distance2;
                if (better(d2, s, best)) {
                    best = {static_cast<int32_t>(s), d2};
                    bestDistance = std::sqrt(d2);
                }
            }
            continue;
        }
        const Node& l = nodes_[n.left];
        const Node& r = nodes_[n.right];
        Entry el{n.left, axisDistance2(l.a, l.ab, l.invLength2, p)};
        Entry er{n.right, axisDistance2(r.a, r.ab, r.invLength2, p)};
        const bool leftFirst = el.axis2 - l.radius * l.radius <= er.axis2 - r.radius * r.radius;
        const Entry& nearer = leftFirst ? el : er;
        const Entry& farther = leftFirst ? er : el;
        if (!prunable(farther.axis2, nodes_[farther.node])) stack[top++] = farther;
        if (!prunable(nearer.axis2, nodes_[nearer.node])) stack[top++] = nearer;
    }
    return best.segment == kNone ? Nearest{} : best;
}

ChainTrees::Nearest ChainTrees::nearestByScan(uint32_t chain, const Vec3& p,
                                              double maxDistance2) const {
    Nearest best{kNone, maxDistance2};
    for (uint32_t s = chainFirst_[chain]; s < chainEnd_[chain]; ++s) {
        const double d2 = project(segments_[s], p).distance2;
        if (better(d2, s, best)) best = {static_cast<int32_t>(s), d2};
    }
    return best.segment == kNone ? Nearest{} : best;
}

double ChainTrees::candidatesByScan(uint32_t chain, const Vec3& lo, const Vec3& hi,
                                    uint32_t nearestToCentre, std::vector<uint32_t>& out) const {
    const BoxQuery box = boxQuery(lo, hi, nearestToCentre);
    for (uint32_t s = chainFirst_[chain]; s < chainEnd_[chain]; ++s)
        if (project(segments_[s], box.centre).distance2 <= box.keep2 && mayBeNearest(s, box))
            out.push_back(s);
    return box.farthest;
}

}  // namespace nenrin
