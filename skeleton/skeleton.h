#pragma once
/// The tree skeleton: the geometry Momoi's growth-time field is computed over.
///
/// A skeleton is a set of chains (polylines): chain 0 is the trunk, the others are branches, each
/// starting on its parent chain. Nodes carry their position (tree space: metres, +Z up, trunk
/// base at the origin) and birth time (years: when the growth tip reached them). Segments carry
/// the per-segment growth properties of the model: radial-speed factor gamma (branch / trunk),
/// dieback time Tlim and exponent eps (eq. 10). Segment ids are contiguous per chain, in chain
/// order, so "the segments of chain c" is the range [chain.firstSegment, +segmentCount).

#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "util/vec3.h"

namespace nenrin {

enum class SegmentKind : uint8_t { Trunk, Branch };

struct SkeletonNode {
    Vec3 position;
    double birthTime = 0;  ///< years after the tree started growing
    double radius = 0;     ///< m, the wood's radius here at the skeleton's age; 0 = unknown
                           ///< (only previews use it; the grain comes from the growth field)
};

inline constexpr double kNeverDies = std::numeric_limits<double>::infinity();
inline constexpr int32_t kNone = -1;

struct SkeletonSegment {
    uint32_t from = 0, to = 0;  ///< node ids; growth runs from -> to
    uint32_t chain = 0;         ///< chain id
    SegmentKind kind = SegmentKind::Trunk;
    uint8_t order = 0;              ///< 0 trunk, 1 first-order branch, ...
    int32_t parent = kNone;         ///< previous segment in the chain, or for a chain's first
                                    ///< segment the parent chain's segment it starts on
    int32_t previous = kNone;       ///< previous segment of the same chain (joint blend)
    int32_t next = kNone;           ///< next segment of the same chain (joint blend)
    double gamma = 1;               ///< radial speed factor: branch / trunk (eq. 3')
    double deathTime = kNeverDies;  ///< Tlim: the branch stops thickening after this (eq. 10)
    double diebackExponent = 0;     ///< eps of eq. 10
};

struct SkeletonChain {
    SegmentKind kind = SegmentKind::Trunk;
    uint8_t order = 0;
    int32_t parentChain = kNone;
    uint32_t firstSegment = 0, segmentCount = 0;
};

/// Properties of a chain to be added (all segments of the chain share them).
struct ChainProperties {
    double gamma = 1;
    double deathTime = kNeverDies;
    double diebackExponent = 0;
};

class Skeleton {
public:
    /// Adds the trunk (must be the first chain). Birth times are per point; radii (m) are per
    /// point too, or empty for "unknown".
    void addTrunk(const std::vector<Vec3>& points, const std::vector<double>& birthTimes,
                  const std::vector<double>& radii = {});
    /// Adds a branch chain whose first point lies on segment `parentSegment` of another chain.
    /// Returns the chain id.
    uint32_t addBranch(uint32_t parentSegment, const std::vector<Vec3>& points,
                       const std::vector<double>& birthTimes, const ChainProperties& props,
                       const std::vector<double>& radii = {});

    /// The tree's yearly radial growth: entry k is the width (m) of the ring the trunk laid
    /// down between years k and k+1. Empty = the grain's constant radial speed. Growth models
    /// that simulate the tree's life (suppression, release) fill it.
    const std::vector<double>& ringWidths() const { return ringWidths_; }
    void setRingWidths(std::vector<double> widths) { ringWidths_ = std::move(widths); }
    /// Entry k: the share of ring k that is late wood (measured earlywood/latewood pairs).
    /// Empty = the grain's transition (or its ring model's yearly shares).
    const std::vector<double>& latewoodShares() const { return latewoodShares_; }
    void setLatewoodShares(std::vector<double> shares) { latewoodShares_ = std::move(shares); }

    const std::vector<SkeletonNode>& nodes() const { return nodes_; }
    const std::vector<SkeletonSegment>& segments() const { return segments_; }
    const std::vector<SkeletonChain>& chains() const { return chains_; }
    const SkeletonSegment& segment(uint32_t i) const { return segments_[i]; }
    const SkeletonChain& chain(uint32_t i) const { return chains_[i]; }
    const SkeletonNode& node(uint32_t i) const { return nodes_[i]; }
    Vec3 start(const SkeletonSegment& s) const { return nodes_[s.from].position; }
    Vec3 end(const SkeletonSegment& s) const { return nodes_[s.to].position; }

    bool empty() const { return chains_.empty(); }
    size_t trunkSegmentCount() const { return chains_.empty() ? 0 : chains_[0].segmentCount; }
    size_t branchSegmentCount() const { return segments_.size() - trunkSegmentCount(); }
    /// Largest gamma over all branch segments (0 without branches).
    double maxBranchGamma() const;

private:
    uint32_t addChain(SegmentKind kind, uint8_t order, int32_t parentChain, int32_t parentSegment,
                      const std::vector<Vec3>& points, const std::vector<double>& birthTimes,
                      const std::vector<double>& radii, const ChainProperties& props);

    std::vector<SkeletonNode> nodes_;
    std::vector<SkeletonSegment> segments_;
    std::vector<SkeletonChain> chains_;
    std::vector<double> ringWidths_;
    std::vector<double> latewoodShares_;
};

/// The pith (trunk axis) position at height z, or the nearest trunk end.
Vec3 pithAtHeight(const Skeleton& skeleton, double z);

}  // namespace nenrin
