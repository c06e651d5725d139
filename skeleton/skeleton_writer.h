#pragma once
/// Writes a Skeleton as a skeleton file (docs/skeleton-format.md) that loads back to the same
/// skeleton: every chain as a polyline with explicit birth times (and radii when known), each
/// branch nested in its parent and placed by its exact start point. Tree generators and
/// importers (`nenrin tree ...`) save their trees with it.

#include <nlohmann/json.hpp>
#include <string>

#include "skeleton/skeleton.h"

namespace nenrin {

struct SkeletonFileInfo {
    std::string description;
    /// Provenance written as the file's "source" object (model, preset, seed, years, input
    /// file, ...). Free-form: nenrin does not read it back.
    nlohmann::json source = nlohmann::json::object();
};

nlohmann::json skeletonToJson(const Skeleton& skeleton, const SkeletonFileInfo& info);

/// Writes the file atomically (no partial file on failure). Throws InputError when `path`
/// cannot be written.
void saveSkeletonFile(const Skeleton& skeleton, const SkeletonFileInfo& info,
                      const std::string& path);

}  // namespace nenrin
