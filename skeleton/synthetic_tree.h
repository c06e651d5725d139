#pragma once
/// A seeded random tree of a requested size: a gently wandering trunk with straight-ish,
/// bending branches at random heights and azimuths, some of them dead. Used by tests (random
/// skeletons for index agreement) and by the benchmark (100 to 100k segments).

#include <cstdint>

#include "skeleton/skeleton.h"

namespace nenrin {

struct SyntheticTreeOptions {
    uint64_t seed = 1;
    size_t totalSegments = 1000;  ///< trunk + branch segments (approximately, >= trunk)
    size_t trunkSegments = 200;
    size_t segmentsPerBranch = 10;
    double height = 20;          ///< m
    double elongationSpeed = 1;  ///< m/year
    double branchLength = 2;     ///< m (mean)
    double deadFraction = 0.3;   ///< share of branches that die
};

Skeleton makeSyntheticTree(const SyntheticTreeOptions& options);

}  // namespace nenrin
