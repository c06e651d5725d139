#pragma once
/// The nearest segment of one branch chain to a point, in time logarithmic in the chain's
/// segment count. Measured and simulated trees have branches of hundreds of segments; a
/// point near a branch needs only the few that a bound cannot rule out, so the field's cost
/// stays flat as polylines get finer.
///
/// Per chain, a balanced binary hierarchy over runs of consecutive segments, each run bounded
/// by a capsule: the segment from the run's first joint to its last, and the largest distance
/// of a joint from it. A polyline hugs that axis, so the bound is tight where an axis-aligned
/// box around a slanting branch would be loose.
///
/// Answers are those of a plain loop with project(): the smallest squared distance, ties to
/// the smaller id, so the field's results do not depend on how the search is done. The loop
/// itself is kept: it is the reference (IndexBackend::BruteForce).

#include <cstdint>
#include <span>
#include <vector>

#include "grain/field_segment.h"
#include "skeleton/skeleton.h"

namespace nenrin {

class ChainTrees {
public:
    ChainTrees() = default;
    /// `segments` must outlive the trees (the field's flattened segments). `hierarchical`
    /// false: every query is a plain loop over the chain (the brute-force reference).
    ChainTrees(std::span<const FieldSegment> segments, std::span<const SkeletonChain> chains,
               bool hierarchical = true);

    struct Nearest {
        int32_t segment = kNone;  ///< kNone if no segment lies within the limit
        double distance2 = 0;     ///< squared distance, as project() computes it
    };
    /// The segment of `chain` nearest to p whose squared distance is <= maxDistance2.
    Nearest nearest(uint32_t chain, const Vec3& p, double maxDistance2) const;
    /// Appends, in id order, a superset of the segments of `chain` that are the nearest of
    /// the chain (as nearest() picks it) for some point of the box [lo, hi]. `nearestToCentre`:
    /// the chain's nearest segment to the box's centre. Typically the few segments the box
    /// projects onto, however long the chain is.
    /// Returns a bound on the distance from any point of the box to the chain (for narrow()).
    double candidates(uint32_t chain, const Vec3& lo, const Vec3& hi, uint32_t nearestToCentre,
                      std::vector<uint32_t>& out) const;

    /// Appends, in their order, those of `segments` (one chain's) that may be the chain's
    /// nearest for some point of the box [lo, hi]: the slab test of candidates() alone, for
    /// narrowing a tile's candidates to a part of the tile.
    /// `farthest`: a bound on the distance from any point of the box to the chain, such as
    /// candidates() returned for a box holding this one.
    void narrow(std::span<const uint32_t> segments, const Vec3& lo, const Vec3& hi, double farthest,
                std::vector<uint32_t>& out) const;

    /// The same two by plain loops over the chain.
    Nearest nearestByScan(uint32_t chain, const Vec3& p, double maxDistance2) const;
    double candidatesByScan(uint32_t chain, const Vec3& lo, const Vec3& hi,
                            uint32_t nearestToCentre, std::vector<uint32_t>& out) const;

private:
    /// A run of segments [first, last) of one chain inside a capsule.
    struct Node {
        Vec3 a, ab;         ///< the capsule's axis: first joint, last joint - first
        double invLength2;  ///< 1 / |ab|^2, 0 if the run closes on itself
        double radius;      ///< largest distance of a joint from the axis, rounded up
        Vec3 axis;          ///< unit ab (0 if the run closes on itself)
        double length;      ///< |ab|
        /// Largest sine of the angle between the axis and a segment of the run or its chain
        /// neighbours (1 past a right angle), rounded up.
        double sinSpread;
        uint32_t first, last;  ///< segment ids covered
        uint32_t left, right;  ///< child nodes; left == 0 for a leaf (node 0 is a root)
    };
    uint32_t build(uint32_t first, uint32_t last);
    /// The box's extent and what bounds the nearest point of the chain for its points.
    struct BoxQuery {
        Vec3 centre, half;
        double keep2;     ///< no candidate is farther than sqrt(keep2) from the centre
        double farthest;  ///< no point of the box is farther than this from the chain
        /// A neighbour rules a segment out only where the box lies past their joint's plane,
        /// into the neighbour, by more than this (m): the neighbour is then nearer by more
        /// than the rounding of the two squared distances.
        double jointMargin;
    };
    /// A box query from its centre, half-extent and farthest distance.
    static BoxQuery makeBoxQuery(const Vec3& centre, const Vec3& half, double farthest);
    BoxQuery boxQuery(const Vec3& lo, const Vec3& hi, uint32_t nearestToCentre) const;
    /// False if no point of the box can have this segment as the nearest of its chain.
    bool mayBeNearest(uint32_t segment, const BoxQuery& box) const;
    Nearest search(uint32_t chain, const Vec3& p, double maxDistance2) const;

    std::span<const FieldSegment> segments_;
    bool hierarchical_ = true;
    std::vector<Node> nodes_;
    std::vector<uint32_t> roots_;  ///< per chain
    std::vector<uint32_t> chainFirst_, chainEnd_;
};

}  // namespace nenrin
