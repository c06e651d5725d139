#pragma once
// Small skeletons built in code for the tests.

#include "skeleton/skeleton.h"

namespace nenrin::test {

/// A straight vertical trunk from the origin to (0, 0, height), births z / Sa.
inline Skeleton straightTrunk(double height = 10, double elongationSpeed = 0.5) {
    Skeleton s;
    s.addTrunk({{0, 0, 0}, {0, 0, height}}, {0, height / elongationSpeed});
    return s;
}

/// A straight trunk with one branch leaving at height h in direction d (unit), births by Sa.
inline Skeleton trunkWithBranch(double h, Vec3 d, double branchLength, ChainProperties props,
                                double height = 10, double sa = 0.5) {
    Skeleton s;
    s.addTrunk({{0, 0, 0}, {0, 0, h}, {0, 0, height}}, {0, h / sa, height / sa});
    Vec3 q{0, 0, h};
    s.addBranch(1, {q, q + d * branchLength}, {h / sa, (h + branchLength) / sa}, props);
    return s;
}

}  // namespace nenrin::test
