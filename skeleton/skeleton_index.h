#pragma once
/// Geometric questions about a skeleton, answered fast: the nearest trunk segment and the branch
/// segments within a radius. One index per class (trunk, branch): a single scene would have to
/// keep its search radius at the larger of the two answers and is ~100x slower
/// (docs/design/embree.md).

#include <memory>

#include "skeleton/segment_index.h"
#include "skeleton/skeleton.h"

namespace nenrin {

enum class IndexBackend {
    Embree,      ///< Embree 3 BVH point queries
    BruteForce,  ///< plain loops: the reference
    Automatic,   ///< brute force for tiny classes, Embree otherwise
};

class SkeletonIndex {
public:
    /// The skeleton must outlive the index.
    explicit SkeletonIndex(const Skeleton& skeleton,
                           IndexBackend backend = IndexBackend::Automatic);

    const Skeleton& skeleton() const { return *skeleton_; }
    const SegmentIndex& trunk() const { return *trunk_; }
    const SegmentIndex& branches() const { return *branches_; }
    /// The branch chains, as capsules around runs of kChainPieceLength segments: gather()
    /// returns chain ids (a chain once per piece near the point). Runs of 256: a finely divided
    /// branch is then one or two capsules (each one the gather meets costs a callback and a
    /// sort entry: with 32 the 100k-segment bench tree's batches met ~170, 5 % of the field's
    /// time), while a long curving branch is still cut into capsules that hug it.
    const SegmentIndex& branchChains() const { return *branchChains_; }
    static constexpr uint32_t kChainPieceLength = 256;
    /// The backend asked for: users that build structures of their own (the growth field's
    /// per-chain hierarchies) follow it, so BruteForce stays plain loops throughout.
    IndexBackend backend() const { return backend_; }

private:
    const Skeleton* skeleton_;
    IndexBackend backend_;
    std::unique_ptr<SegmentIndex> trunk_;
    std::unique_ptr<SegmentIndex> branches_;
    std::unique_ptr<SegmentIndex> branchChains_;
};

}  // namespace nenrin
