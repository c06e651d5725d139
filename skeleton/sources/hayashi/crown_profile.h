#pragma once
/// The parabolic crown of Hayashi & Takahashi (eq. 1-2, after Takeshita 1985):
///
///     y = a (1 - z)^0.5,   y = branch length / tree height,  z = branch height / tree height.
///
/// A first-order branch at height zb of a tree of height H is a H sqrt(1 - zb / H) long; as the
/// tree grows the same branch lengthens, so the inverse (which tree height makes the branch reach
/// a given length) gives the time its tip passed each point.

#include <algorithm>
#include <cmath>

namespace nenrin {

/// Branch length (m) of eq. 2 for a branch at `branchHeight` on a tree `treeHeight` tall
/// (0 above the top).
inline double crownBranchLength(double a, double treeHeight, double branchHeight) {
    if (treeHeight <= branchHeight) return 0;
    return a * std::sqrt(treeHeight * (treeHeight - branchHeight));
}

/// The tree height at which a branch at `branchHeight` reaches `branchLength` by eq. 2:
/// the root of H^2 - zb H - (l / a)^2 = 0 that is >= zb.
inline double treeHeightForBranchLength(double a, double branchHeight, double branchLength) {
    double q = branchLength / a;
    return 0.5 * (branchHeight + std::sqrt(branchHeight * branchHeight + 4 * q * q));
}

}  // namespace nenrin
