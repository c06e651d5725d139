#pragma once
/// Momoi's growth-time field: T(P) = time at which the bark surface first reaches P.
///
/// For a point P (after sway), the trunk path gives T1 (nearest trunk point N, Ta from the node
/// birth times, Tb from the distance with direction, taper, age and jitter terms; polyline
/// joints blended by eq. 4). Every branch chain near enough gives its own path time T2 the same
/// way (gamma Sb, dieback eq. 10). Trunk and branch paths are joined by the smooth minimum of
/// eq. 5 (our reconstruction) taken over all branch paths at once:
///   T = (T1^-p + sum_c w_c (T_c / sin alpha_c)^-p)^(-1/p),
/// alpha_c measured from the plane through the branch's start perpendicular to it, w_c the
/// reach cut-off weight of T_c / sin alpha_c (junctionReachWeight). With one branch and
/// w_c = 1 this is exactly eq. 5.
///
/// Points come in batches (tiles of a bake): one set of candidate segments is gathered from the
/// index for the whole batch and every point is then evaluated against it. The answer for a
/// point never depends on the batch it came in: candidate lists are supersets, sorted by id,
/// filtered per point, so results are bitwise identical for any tiling and thread count.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "grain/chain_tree.h"
#include "grain/field_segment.h"
#include "grain/grain_params.h"
#include "grain/growth_terms.h"
#include "grain/latewood_timing.h"
#include "grain/point_quarters.h"
#include "grain/radial_growth.h"
#include "grain/segment_batch.h"
#include "skeleton/skeleton_index.h"

namespace nenrin {

/// The field is evaluated within this many metres of the tree's origin on each axis; farther
/// points are moved onto that edge (squared distances must not overflow).
inline constexpr double kFieldDomain = 1e100;

struct GrowthSample {
    double T = 0;                 ///< growth time, years, all terms applied
    double trunkTime = 0;         ///< T1: the trunk path's time
    double Ta = 0, Tb = 0;        ///< elongation and thickening parts of the trunk path
    Vec3 axisPoint;               ///< N: nearest trunk point
    Vec3 axisDirection;           ///< trunk tangent at N
    double knot = 0;              ///< share of branch paths in the junction blend, 0..1
    double deadKnot = 0;          ///< share of branches that had died before the trunk reached P
                                  ///< (encased dead knots), 0..knot
    int32_t knotChain = -1;       ///< branch chain with the largest share, -1 if none
    double knotAxisDistance = 0;  ///< distance to that chain's axis (m), 0 without one
    /// The knot's section radius (m) on the ray from the chain's axis through P: where the
    /// trunk's growth meets the branch's, the knot's edge (for a dead knot, where its bark
    /// lies encased). 0 without a chain.
    double knotRadius = 0;
    bool knotDied = false;   ///< that chain had died before the trunk reached P
    Vec3 knotOffset;         ///< P minus the nearest point of that chain's axis (its pith)
    Vec3 knotAxisDirection;  ///< the chain's tangent there, pointing out of the trunk
};

/// Reusable per-thread buffers for batch evaluation.
struct GrowthScratch {
    std::vector<Vec3> points;
    std::vector<uint32_t> trunkCandidates;
    std::vector<uint32_t> chunkTrunk;  ///< trunk candidates kept for the current chunk
    /// A branch chain near the current tile, with the segments that may matter for it.
    struct TileChain {
        uint32_t chain;
        /// Per quarter of the chunk: the range in keptSegments that may matter for its points.
        std::array<uint32_t, 4> begin, end;
        Vec3 start, direction;  ///< Q and the normal of plane F (eq. 5)
        double gamma;           ///< largest gamma of the kept segments and their neighbours
        double birthBound;      ///< smallest node birth time they can use
        Vec3 lower, upper;      ///< bounding box of the kept segments
    };
    std::vector<TileChain> tileChains;
    SegmentBatch keptSegments;
    std::vector<uint32_t> candidateChains;  ///< chains with a segment near the batch, sorted
    std::vector<uint32_t> groupChains;      ///< those that may matter for a group of chunks
    std::vector<uint32_t> chainSegments;    ///< one chain's segments near the tile
    std::vector<uint32_t> quarterSegments;  ///< those that may matter for one quarter
    PointQuarters quarters;  ///< of the current chunk, split when a chain first needs it
    std::vector<double> centreDistances;
    struct ChainTerm {
        uint32_t chain;
        double time, sinAlpha, distance;
        double dead;    ///< 0 living, 1 dead when the trunk reached P
        double weight;  ///< the reach cut-off weight w_c
        uint32_t segment;
        Vec3 axisPoint, axisDirection;
        double Ta, Tb;  ///< the nearest segment's own (unblended) elongation and thickening
    };
    std::vector<ChainTerm> terms;
};

class GrowthField {
public:
    /// The index (and its skeleton) must outlive the field.
    GrowthField(const SkeletonIndex& index, const GrainParams& params);
    /// Not copyable: the chain hierarchies point into the field's own segments.
    GrowthField(const GrowthField&) = delete;
    GrowthField& operator=(const GrowthField&) = delete;

    const GrainParams& params() const { return params_; }
    const Skeleton& skeleton() const { return index_->skeleton(); }

    GrowthSample evaluate(const Vec3& p) const;
    /// When each year's late wood begins: the skeleton's measured latewood shares, or the
    /// ring model's (narrow rings carry relatively more late wood); empty otherwise.
    const LatewoodTiming& latewoodTiming() const { return latewoodTiming_; }
    /// Evaluates a batch. Spatially coherent batches are much faster than scattered ones: the
    /// index is queried once per batch and candidates are pruned per run of 64 consecutive
    /// points, so order points in compact groups of 64 (8 x 8 tiles) within larger batches.
    /// `stencil` > 1: points come in runs of that many around their first point (a finite
    /// difference stencil a fraction of a ring wide), and the whole run is swayed by its first
    /// point's displacement. Sway bends rings over decimetres, so this changes a gradient by
    /// about 2 % (its slope) and spares the sway sums of the other points of the run.
    void evaluateBatch(std::span<const Vec3> points, std::span<GrowthSample> out,
                       GrowthScratch& scratch, size_t stencil = 1) const;

    /// One path: the time through segment `segment` (with the eq. 4 joint blend of its chain
    /// neighbours). Exposed for tests.
    struct PathTime {
        double T, Ta, Tb;
        Vec3 axisPoint, axisDirection;
        double distance;
    };
    PathTime chainPathTime(uint32_t segment, const Vec3& p) const;

private:
    PathTime segmentPathTime(uint32_t segment, const Vec3& p, double t) const;
    /// Radius (m) on the ray from the segment's axis through P (`path` = segmentPathTime at P)
    /// at which its path time, before dieback, is `time`: path times scale with distance
    /// along such a ray through the radial growth and the age warp only, both invertible.
    double radiusAtTime(uint32_t segment, const PathTime& path, double time) const;
    /// Fills the sample's knot geometry from the branch path with the largest share.
    void describeKnot(const GrowthScratch::ChainTerm& term, const Vec3& point, double trunkTime,
                      GrowthSample& sample) const;
    double branchSearchRadius(double trunkTime) const;
    /// True if every point of the box projects strictly inside the segment's slab and lies
    /// past the previous segment's end and before the next one's start (so the neighbours'
    /// nearest points are the shared joints, and eq. 4 needs no blend).
    bool insideSlabOnly(uint32_t segment, const Vec3& lo, const Vec3& hi) const;
    void evaluateBranches(std::span<const Vec3> points, std::span<GrowthSample> out,
                          GrowthScratch& scratch) const;
    /// Tests 1-3 of prepareTileChains for one chain: false if it cannot matter for any point
    /// of the ball (centre, radius) around the box [lo, hi], given the largest trunk time
    /// there; else the reach time of the ball and the chain's segment nearest to its centre.
    struct ChainReach {
        double reachTime;
        ChainTrees::Nearest nearest;
    };
    bool chainMayMatter(uint32_t chain, const Vec3& lo, const Vec3& hi, const Vec3& centre,
                        double radius, double maxTrunkTime, ChainReach& out) const;
    void prepareTileChains(GrowthScratch& scratch, std::span<const uint32_t> candidates,
                           const Vec3& lo, const Vec3& hi, double halfDiagonal,
                           double maxTrunkTime) const;

    const SkeletonIndex* index_;
    GrainParams params_;
    SwayWaves sway_;
    std::vector<FieldSegment> segments_;  ///< the skeleton's segments, flattened
    ChainTrees chainTrees_;               ///< each chain's nearest-segment hierarchy
    /// Per chain: Q and the normal of plane F (eq. 5), and bounds over all its segments.
    struct ChainFrame {
        Vec3 start, direction;
        double birthBound, gammaBound;
        double deathBound, diebackBound;  ///< the latest death, the smallest dieback exponent
    };
    std::vector<ChainFrame> chainFrames_;
    double maxGamma_;            ///< largest branch gamma of the skeleton
    RadialGrowth radialGrowth_;  ///< the skeleton's ring widths; empty = constant speed Sb
    LatewoodTiming latewoodTiming_;
    double speedBound_;  ///< largest radial speed of any path over gamma, m/year
};

}  // namespace nenrin
