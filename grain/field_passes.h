#pragma once
/// What the growth field's passes hand each other (GrowthField::evaluateBatch: sway, trunk,
/// chain culls, branches), and the buffers they reuse from batch to batch, which a
/// GrowthScratch holds. Internal to grain/.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "grain/field_bounds.h"
#include "grain/field_segment.h"
#include "grain/point_box.h"
#include "grain/point_quarters.h"
#include "grain/segment_batch.h"
#include "grain/segment_lanes.h"
#include "util/vec3.h"

namespace nenrin {

/// Points per chunk: the unit of candidate pruning inside a batch (an 8 x 8 tile).
inline constexpr size_t kChunk = kLanes;

/// The nearest segment found so far. Candidates are visited in id order and only a strictly
/// smaller distance replaces it, so ties go to the smaller id, like the indexes.
struct Best {
    int32_t segment = kNone;
    double distance2 = kInf;
};

/// A branch chain near a chunk, with the segments that may matter for it.
struct TileChain {
    uint32_t chain;
    /// Per quarter of the chunk: the range in TileChains::segments that may matter for its
    /// points.
    std::array<uint32_t, 4> begin, end;
    Vec3 start, direction;  ///< Q and the normal of plane F (eq. 5)
    double gamma;           ///< largest gamma of the kept segments and their neighbours
    double birthBound;      ///< smallest node birth time they can use
    Vec3 lower, upper;      ///< bounding box of the kept segments
};

/// The chain culls' answer for one chunk (GrowthField::prepareTileChains), the branch pass's
/// input (GrowthField::evaluateBranches).
struct TileChains {
    std::vector<TileChain> chains;
    /// The kept segments of all of them, laid out for the vectorised nearest-segment pass
    /// (which measures into a buffer of its own: the branch pass takes them non-const).
    SegmentBatch segments;
};

/// A branch path's term in one point's junction blend (eq. 5).
struct BranchTerm {
    uint32_t chain;
    double time, sinAlpha, distance;
    double dead;    ///< 0 living, 1 dead when the trunk reached P
    double weight;  ///< the reach cut-off weight w_c
    uint32_t segment;
    Vec3 axisPoint, axisDirection;
    double Ta, Tb;  ///< the nearest segment's own (unblended) elongation and thickening
};

/// One tile chain's cheap tests at a chunk's points (grain/reach_lanes.h); its path cannot
/// count at a point where passes() is false.
struct ReachLanes {
    std::array<double, kLanes> sinAlpha;  ///< eq. 5's angle from plane F, as a sine
    std::array<double, kLanes> slack;     ///< reach x T1 sin(alpha) less the chain's birth bound
    std::array<double, kLanes> radius2;   ///< no segment farther than sqrt of this can count
    std::array<double, kLanes> outside2;  ///< squared distance to the kept segments' box
    bool passes(size_t i) const {
        return !(sinAlpha[i] <= 0 || slack[i] <= 0 || outside2[i] > radius2[i]);
    }
};

/// What becomes of a chain at a lane's point.
enum class LaneState : int32_t {
    kNone = 0,     ///< no term: a test drops it, or its weight is 0
    kTerm = 1,     ///< a term, all of it in the lanes
    kDieback = 2,  ///< a term whose time T is past its segment's death: eq. 10 (a pow) is to
                   ///< be applied to T, then the weight computed, by the caller
    kScalar = 3,   ///< P lies in a neighbour's slab too (eq. 4's blend): the per-point code
};

/// One tile chain at the lanes of a NearestLanes (grain/branch_lanes.h).
struct BranchLanes {
    std::array<double, kLanes> state;       ///< a LaneState (a double: one lane type)
    std::array<double, kLanes> T;           ///< path time (before dieback where kDieback)
    std::array<double, kLanes> Ta, Tb;      ///< its elongation and thickening parts
    std::array<double, kLanes> distance;    ///< from P to the axis point
    std::array<double, kLanes> ax, ay, az;  ///< the axis point
    std::array<double, kLanes> weight;      ///< junctionReachWeight (kTerm lanes)
    std::array<double, kLanes> dead;        ///< the encased-knot share (kTerm, kDieback)
};

/// The branch pass's buffers, for one chunk.
struct BranchBuffers {
    PointLanes points;
    std::array<double, kLanes> trunkTimes;  ///< the points' T1
    std::vector<ReachLanes> reach;          ///< per tile chain: reachTests' answers
    /// The chunk's points grouped by quarter (when a chain's kept segments differ by quarter):
    /// each quarter's points, compact, and each point's place among its quarter's.
    std::array<PointLanes, 4> quarterPoints;
    std::array<size_t, 4> quarterCount;
    std::array<uint8_t, kLanes> placeInQuarter;
    /// Per tile chain and quarter: the index in `nearest` of the lanes holding its points'
    /// nearest kept segments (-1: not measured, each point measures them itself).
    std::vector<std::array<int32_t, 4>> nearestOf;
    /// Per tile chain: 1 if those lanes are indexed by the point's place in its quarter, 0 if
    /// by the point.
    std::vector<uint8_t> byQuarter;
    std::vector<NearestLanes> nearest;
    /// Per entry of `nearest`: the chain's tests, path and term at those lanes, filled for
    /// whole-chunk entries with plain thickening (grain/branch_lanes.h).
    std::vector<BranchLanes> paths;
    /// Per tile chain: its lanes in `paths` and `nearest` where taken for the whole chunk.
    struct TakenLanes {
        const BranchLanes* terms = nullptr;
        const NearestLanes* nearest = nullptr;
    };
    std::vector<TakenLanes> taken;
    std::vector<BranchTerm> terms;  ///< of the current point
};

/// The trunk pass's lists.
struct TrunkBuffers {
    std::vector<uint32_t> candidates;  ///< trunk segments near the batch, sorted
    std::vector<uint32_t> kept;        ///< those kept for the current chunk
    std::vector<double> centreDistances;
    PointLanes points;                ///< a chunk's points
    SegmentLanes lanes;               ///< on their plain segment
    NearestLanes nearest;             ///< or their nearest kept segment
    std::vector<double> chunkMaxima;  ///< each chunk's largest T1
};

/// The chain culls' lists for one chain.
struct CullBuffers {
    std::vector<uint32_t> chainSegments;    ///< one chain's segments near the chunk
    std::vector<uint32_t> quarterSegments;  ///< those that may matter for one quarter
};

/// GrowthScratch's innards: the buffers of one evaluateBatch call, reused by the next.
struct GrowthBuffers {
    std::vector<Vec3> points;          ///< the batch's points, swayed
    std::vector<PointBox> chunkBoxes;  ///< around each chunk of them
    TrunkBuffers trunk;
    std::vector<uint32_t> candidateChains;  ///< chains that may matter for the batch, sorted
    std::vector<uint32_t> groupChains;      ///< those that may matter for a group of chunks
    PointQuarters quarters;                 ///< of the current chunk
    CullBuffers cull;
    TileChains tileChains;  ///< of the current chunk
    BranchBuffers branch;
};

}  // namespace nenrin
