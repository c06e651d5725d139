#include "grain/grown_tree.h"

#include <utility>

#include "skeleton/skeleton_file.h"

namespace nenrin {

GrownTree::GrownTree(Skeleton skeleton, GrainParams grain)
    : skeleton_(std::move(skeleton)),
      grain_(std::move(grain)),
      index_(skeleton_),
      field_(index_, grain_) {}

std::unique_ptr<GrownTree> GrownTree::load(const std::string& skeletonFile,
                                           const std::string& grainFile) {
    Skeleton skeleton = loadSkeletonFile(skeletonFile);
    GrainParams grain = grainFile.empty() ? GrainParams{} : loadGrainFile(grainFile);
    return std::make_unique<GrownTree>(std::move(skeleton), std::move(grain));
}

}  // namespace nenrin
