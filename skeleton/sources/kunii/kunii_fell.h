#pragma once
/// Felling a tree of a simulated stand (kunii_stand.h): an A-system skeleton (a_system_tree.h)
/// sized to the tree's final height and crown, whose timing comes from the tree's life:
/// - the leader reached height h in the year its height history passed h (node birth times);
/// - a lateral lives from the year the leader passed its fork until the crown base rose past
///   it (deathTime: a dead knot), and is only as long as it had grown by then;
/// - the rings: entry k is the stem radius gained in the tree's year k (suppressed years are
///   narrow, a release widens them).
/// Times in the skeleton are tree ages (years since the tree's first year).

#include <cstdint>
#include <string>
#include <vector>

#include "skeleton/skeleton.h"
#include "skeleton/sources/kunii/a_system_tree.h"
#include "skeleton/sources/kunii/kunii_stand.h"

namespace nenrin {

/// The default form of a felled tree: preset "aono-kunii-b" with a persistent leader of 20
/// forks (20 limbs to become knots) whose laterals keep at most 6 forks.
ASystemParams defaultFellForm();

struct FellOptions {
    ASystemParams form = defaultFellForm();
    /// Scales the trunk's A-system deflection (0 = straight stem, 1 = as the A-system).
    double trunkSway = 0.2;
    /// Rings narrower than this (m) are written as this: a year without growth still leaves
    /// a (microscopic) ring, and skeleton files need widths > 0.
    double minRingWidth = 1e-5;
};

/// Ring widths (m) of a stand tree: entry k = stem radius at the end of its year k minus that
/// at the end of year k - 1 (entry 0 is the radius after the first year: the seedling's stem
/// and its first ring), at least minRingWidth. Their sum is the final stem radius.
std::vector<double> standTreeRingWidths(const StandTree& tree, double minRingWidth = 1e-5);

/// The felled tree. Throws InputError if the id is not in the stand or the tree never grew.
Skeleton fellStandTree(const Stand& stand, uint32_t treeId, const FellOptions& options = {});

/// Which tree to fell, for the command line and the tests.
enum class TreePick {
    Dominant,    ///< the tallest living tree
    Suppressed,  ///< the living tree (>= 20 years old) with the least light over its last 10
                 ///< years, relative to I0
};
TreePick treePickFromName(const std::string& name);  ///< "dominant", "suppressed"
std::vector<std::string> treePickNames();
/// The id of the picked tree. Throws InputError if no living tree qualifies.
uint32_t pickStandTree(const Stand& stand, TreePick pick);

}  // namespace nenrin
