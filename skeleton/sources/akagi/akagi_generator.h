#pragma once
/// Akagi & Kitajima's recursive tree generator (paper section 2.4, docs/design/models.md §5): a
/// root segment with growth element 100 splits its growth element among BranchNum children (main
/// axis first, then laterals) by MainGrowth / SubGrowth; a child whose growth element falls below 1
/// becomes a leaf cluster; lengths follow the ratio of growth elements, radii the pipe model,
/// directions the angles, rotation and horizontality; the tree is finally scaled so that its top
/// reaches Height.
///
/// The result is mapped onto a Skeleton: the dominant continuation from the root is the trunk
/// (chain 0), every other axis a branch chain continued along its own dominant child. Birth times
/// come from the growth element (log scale: the root is born at 0, the tips at `years`), gamma from
/// each branch's pipe-model radius and age. See docs/tree-akagi.md.

#include <cstdint>
#include <string>
#include <vector>

#include "skeleton/skeleton.h"
#include "skeleton/sources/akagi/akagi_params.h"
#include "util/vec3.h"

namespace nenrin {

/// One segment of the generator (a "growth element" segment of the paper), in tree space.
struct AkagiSegment {
    int32_t parent = kNone;    ///< parent segment, kNone for the root
    int childIndex = 0;        ///< 0 = main axis child, 1.. = laterals
    double growthElement = 0;  ///< the paper's growth element (root 100)
    Vec3 start, end;           ///< m
    double radius = 0;         ///< m, pipe model
    double birthTime = 0;      ///< years, when the tip left `start`
    uint32_t chain = 0;        ///< skeleton chain holding this segment
    uint32_t skeletonSegment = 0;
    std::vector<int32_t> children;  ///< child segments (leaves are not segments)
};

struct AkagiLeaf {
    Vec3 position;    ///< m, where the leaf is attached (a segment tip)
    Vec3 direction;   ///< unit
    double size = 0;  ///< m (LeafSize)
};

struct AkagiTreeStats {
    size_t segmentCount = 0, leafCount = 0, chainCount = 0;
    int maxDepth = 0;
    bool truncated = false;           ///< the element budget ran out (implausible tree)
    double scale = 1;                 ///< metres per unit of the unscaled generator
    double height = 0;                ///< m, top of the tree (== Height after scaling)
    double lowestZ = 0;               ///< m, lowest node (< 0 = below ground)
    double crownWidth = 0;            ///< m, larger of the x and y extents
    double trunkLength = 0;           ///< m, path length of chain 0
    double trunkTopZ = 0;             ///< m, height of the trunk chain's last point
    double trunkStraightness = 0;     ///< chord / path length of chain 0 (1 = straight)
    double mainAxisLength = 0;        ///< m, path length from the root along child 0 (main) only
    double longestBranchLength = 0;   ///< m, longest branch chain
    double firstForkHeight = 0;       ///< m, end of the root segment
    double widestRelativeHeight = 0;  ///< z / Height of the node farthest from the z axis
                                      ///< (low: conical crown, high: vase or umbrella)
};

struct AkagiTree {
    Skeleton skeleton;
    std::vector<AkagiSegment> segments;
    std::vector<AkagiLeaf> leaves;
    AkagiParams params;
    double years = 0;
    AkagiTreeStats stats;
    int attempts = 1;  ///< draws growAkagiSpecies needed for a plausible tree
};

struct AkagiGenerateOptions {
    /// Per-segment angle noise (sd, deg) on the rotation and the laterals' tilt: the paper gives
    /// every segment its own parameters; one parameter set per tree plus this jitter stands in
    /// for that. The main axis keeps MainAngle exactly: noise on it accumulates along the axis
    /// into a leaning leader, which the paper's per-tree parameters do not describe.
    double angleJitterDeg = 3;
    /// Segment length = parent length * (growth element / parent's)^lengthExponent. The paper
    /// says only "according to the ratio"; 1 (proportional) gives laterals so short that no
    /// conifer reaches a conical crown, 0.5 gives crown width / height ratios of real trees.
    double lengthExponent = 0.5;
    /// Budget of segments; a parameter set that needs more is cut off and flagged truncated.
    size_t maxSegments = 100000;
};

/// Generates the tree. `years` (> 0) is the tree's age: the tips are born at `years`. Throws
/// InputError for out-of-range parameters, years or options.
AkagiTree generateAkagiTree(const AkagiParams& params, uint64_t seed, double years,
                            const AkagiGenerateOptions& options = {});

/// The plausibility check the paper suggests (section 4.1) for generated trees: no node below
/// ground, crown width / height in [0.1, 2], leaf count in [20, 200000], trunk top above 0.4
/// Height, trunk slenderness Height / (2 Radius) in [5, 250], no main axis (trunk or first-order
/// branch chain) coming back within 0.2% of Height of itself, not truncated, >= 8 segments.
/// On failure `why` (if given) says which check failed.
bool isPlausible(const AkagiTree& tree, std::string* why = nullptr);

}  // namespace nenrin
