#include "skeleton/skeleton_index.h"

namespace nenrin {

namespace {
// Below this many segments a loop beats a BVH traversal (docs/design/embree.md measurements).
constexpr size_t kBruteForceBelow = 64;

std::unique_ptr<SegmentIndex> makeIndex(SegmentSoup soup, IndexBackend backend) {
    bool brute = backend == IndexBackend::BruteForce ||
                 (backend == IndexBackend::Automatic && soup.ids.size() < kBruteForceBelow);
    return brute ? makeBruteForceSegmentIndex(std::move(soup))
                 : makeEmbreeSegmentIndex(std::move(soup));
}
}  // namespace

SkeletonIndex::SkeletonIndex(const Skeleton& skeleton, IndexBackend backend)
    : skeleton_(&skeleton),
      backend_(backend),
      trunk_(makeIndex(collectSegments(skeleton, SegmentKind::Trunk), backend)),
      branches_(makeIndex(collectSegments(skeleton, SegmentKind::Branch), backend)),
      branchChains_(makeIndex(collectChainPieces(skeleton, kChainPieceLength), backend)) {}

}  // namespace nenrin
