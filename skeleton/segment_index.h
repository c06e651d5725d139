#pragma once
/// Spatial index over one class of skeleton segments (trunk or branch): nearest segment and
/// gather-within-radius queries. Two implementations with identical answers:
///  - EmbreeSegmentIndex: Embree 3 BVH over user-geometry segments, rtcPointQuery;
///  - BruteForceSegmentIndex: a plain loop, kept as the test reference and the fast path for
///    tiny skeletons.
/// Built once, immutable, safe to query from many threads.

#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "skeleton/skeleton.h"

namespace nenrin {

struct NearestSegment {
    int32_t segment = kNone;  ///< global segment id, kNone if nothing within the radius
    double distance2 = std::numeric_limits<double>::infinity();
};

class SegmentIndex {
public:
    virtual ~SegmentIndex() = default;
    /// The segment nearest to p, if any lies within maxRadius. Ties go to the smaller id.
    virtual NearestSegment nearest(
        const Vec3& p, double maxRadius = std::numeric_limits<double>::infinity()) const = 0;
    /// Appends the ids of all segments whose distance to p is <= radius, in no particular order.
    virtual void gather(const Vec3& p, double radius, std::vector<uint32_t>& out) const = 0;
    /// Number of segments indexed.
    virtual size_t size() const = 0;
};

/// The segments of one class, copied out of a skeleton for indexing; or capsules (a segment
/// and a radius: every point within `radius` of it), whose distance to p is the segment's less
/// the radius, at least 0.
struct SegmentSoup {
    std::vector<Vec3> a, b;
    std::vector<uint32_t> ids;   ///< global segment ids (or what the capsules stand for)
    std::vector<double> radius;  ///< per entry; empty for plain segments
};
SegmentSoup collectSegments(const Skeleton& skeleton, SegmentKind kind);
/// Every branch chain as capsules around runs of at most `runLength` consecutive segments,
/// each holding its run; ids are chain ids. A gather from these finds the chains near a point
/// at a cost that does not grow with how finely the chains are divided.
SegmentSoup collectChainPieces(const Skeleton& skeleton, uint32_t runLength);

/// Squared distance from p to entry i of a soup: to the segment, less the capsule's radius.
double soupDistance2(const SegmentSoup& soup, size_t i, const Vec3& p);

std::unique_ptr<SegmentIndex> makeBruteForceSegmentIndex(SegmentSoup soup);
std::unique_ptr<SegmentIndex> makeEmbreeSegmentIndex(SegmentSoup soup);

}  // namespace nenrin
