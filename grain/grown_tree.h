#pragma once
/// A tree ready to be cut: its skeleton, its grain parameters, the skeleton's index and the
/// growth field over them. Every user of the field (a scene's wood, a bake, the shader plugin)
/// builds this one bundle. Built in place and never moved: the index refers to the skeleton,
/// the field to the index.

#include <memory>
#include <string>

#include "grain/grain_params.h"
#include "grain/growth_field.h"
#include "skeleton/skeleton.h"
#include "skeleton/skeleton_index.h"

namespace nenrin {

class GrownTree {
public:
    GrownTree(Skeleton skeleton, GrainParams grain);
    GrownTree(const GrownTree&) = delete;
    GrownTree& operator=(const GrownTree&) = delete;

    /// Reads a skeleton file and a grain file (empty: the default grain); InputErrors name the
    /// file and the place in it.
    static std::unique_ptr<GrownTree> load(const std::string& skeletonFile,
                                           const std::string& grainFile);

    const Skeleton& skeleton() const { return skeleton_; }
    const GrainParams& grain() const { return grain_; }
    const SkeletonIndex& index() const { return index_; }
    const GrowthField& field() const { return field_; }

private:
    Skeleton skeleton_;
    GrainParams grain_;
    SkeletonIndex index_;
    GrowthField field_;
};

}  // namespace nenrin
