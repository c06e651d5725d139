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

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "grain/chain_tree.h"
#include "grain/field_segment.h"
#include "grain/grain_params.h"
#include "grain/growth_terms.h"
#include "grain/latewood_timing.h"
#include "grain/point_box.h"
#include "grain/radial_growth.h"
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

struct GrowthBuffers;  // grain/field_passes.h

/// Reusable per-thread buffers for batch evaluation: make one per thread and pass it to each
/// evaluateBatch call. What it holds is the field's own business (GrowthBuffers,
/// grain/field_passes.h), made on first use; a copy starts empty.
struct GrowthScratch {
    GrowthScratch();
    ~GrowthScratch();
    GrowthScratch(const GrowthScratch&);
    GrowthScratch& operator=(const GrowthScratch&);
    GrowthScratch(GrowthScratch&&) noexcept;
    GrowthScratch& operator=(GrowthScratch&&) noexcept;

private:
    friend class GrowthField;
    GrowthBuffers& buffers();
    std::unique_ptr<GrowthBuffers> buffers_;
};

// What the passes of evaluateBatch hand each other (grain/field_passes.h).
struct TrunkBuffers;
struct CullBuffers;
struct TileChains;
struct BranchTerm;
struct BranchBuffers;
class PointQuarters;

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
    /// The same, with P's projection onto the segment (project()) already at hand (inline,
    /// grain/path_time.h).
    inline PathTime chainPathTime(uint32_t segment, const Vec3& p,
                                  const SegmentProjection& proj) const;
    /// The eq. 4 blend where P lies in a neighbour's slab too: their tRaw, -1 if not in it.
    PathTime blendedPathTime(uint32_t segment, const Vec3& p, double tRaw, double previousT,
                             double nextT) const;
    // One path (inline, grain/path_time.h).
    inline PathTime segmentPathTime(uint32_t segment, const Vec3& p, double t) const;
    /// Its thickening time Tb (eq. 3/3', 7-9, the radial jitter and the ring series) at
    /// distance `distance` = |d| from the axis point where the elongation time is Ta; with
    /// plainThickening_, distance x s.inverseSpeed.
    double thickening(uint32_t segment, double Ta, const Vec3& d, double distance) const;
    /// Radius (m) on the ray from the segment's axis through P (Ta, Tb and distance:
    /// segmentPathTime's at P) at which its path time, before dieback, is `time`: path times
    /// scale with distance along such a ray through the radial growth and the age warp only,
    /// both invertible (inline, grain/path_time.h).
    inline double radiusAtTime(uint32_t segment, double Ta, double Tb, double distance,
                               double time) const;

    // The passes of evaluateBatch after the sway, in order; each hands the next its answer.
    /// The trunk pass (trunk_pass.cpp): every point's trunk path T1 into `out` (the rest of
    /// each sample reset); returns the largest T1 (each chunk's in buffers.chunkMaxima).
    /// `batch`: the points' bounding box, `chunks`: each chunk's.
    double evaluateTrunk(std::span<const Vec3> points, const PointBox& batch,
                         std::span<const PointBox> chunks, std::span<GrowthSample> out,
                         TrunkBuffers& buffers) const;
    // The chain culls (chain_culls.cpp): which branch chains can matter for a box of points.
    double branchSearchRadius(double trunkTime) const;
    /// Tests 1-3 of prepareTileChains for one chain: false if it cannot matter for any point
    /// of the ball (centre, radius) around the box, given the largest trunk time there; else
    /// the reach time of the ball and the chain's segment nearest to its centre.
    struct ChainReach {
        double reachTime;
        ChainTrees::Nearest nearest;
    };
    bool chainMayMatter(uint32_t chain, const PointBox& box, const Vec3& centre, double radius,
                        double maxTrunkTime, ChainReach& out) const;
    /// Tests 1-3 over a ball that holds every chunk's of the box (twice its half-diagonal: a
    /// chunk's centre lies within it, its half-diagonal is at most the box's): what fails here
    /// fails for every chunk in the box.
    bool chainMayMatterInside(uint32_t chain, const PointBox& box, double maxTrunkTime) const;
    /// The branch chains that may matter for the batch (largest trunk time `maxTrunkTime`),
    /// into `chains`, sorted.
    void nearbyChains(const PointBox& batch, double maxTrunkTime,
                      std::vector<uint32_t>& chains) const;
    /// Those of `chains` that may matter for a group of chunks, in `kept`.
    std::span<const uint32_t> cullChains(std::span<const uint32_t> chains, const PointBox& group,
                                         double maxTrunkTime, std::vector<uint32_t>& kept) const;
    /// The chains of `candidates` that may matter for some point of a chunk, with the
    /// segments each quarter of it must measure (splitting `quarters` when a chain needs it).
    void prepareTileChains(std::span<const uint32_t> candidates, const PointBox& chunk,
                           double maxTrunkTime, PointQuarters& quarters, TileChains& out,
                           CullBuffers& buffers) const;
    /// The branch pass (branch_pass.cpp) over one chunk: each point's branch paths among
    /// `chains` and the junction blend (eq. 5) with its trunk path, into `out`.
    void evaluateBranches(std::span<const Vec3> points, const PointQuarters& quarters,
                          TileChains& chains, std::span<GrowthSample> out,
                          BranchBuffers& buffers) const;
    /// Fills the sample's knot geometry from the branch path with the largest share (inline:
    /// defined and used in branch_pass.cpp only).
    inline void describeKnot(const BranchTerm& term, const Vec3& point, double trunkTime,
                             GrowthSample& sample) const;

    const SkeletonIndex* index_;
    GrainParams params_;
    SwayWaves sway_;
    std::vector<FieldSegment> segments_;  ///< the skeleton's segments, flattened
    /// Per segment, the plane its radial jitter's azimuth is measured in (empty without
    /// jitter): the same for every point of the segment, so made once.
    std::vector<SwayFrame> swayFrames_;
    double taperLogOmega_;   ///< ln(omega) of eq. 9: omega^Ta as exp(Ta ln omega)
    ChainTrees chainTrees_;  ///< each chain's nearest-segment hierarchy
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
    /// No taper, direction, radial jitter, age warp or ring series: thickening() is the
    /// distance over the constant speed, and the trunk pass computes it in its vector loop.
    bool plainThickening_ = false;
};

}  // namespace nenrin
