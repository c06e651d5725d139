#pragma once
/// Momoi-style hand-written skeleton files (JSON): a trunk polyline and branches that start on
/// the trunk (or on another branch) with a direction and length. The format is documented in
/// docs/skeleton-format.md; every problem is an InputError naming the file and JSON path.

#include <nlohmann/json.hpp>
#include <string>

#include "skeleton/skeleton.h"

namespace nenrin {

/// Loads a skeleton file.
Skeleton loadSkeletonFile(const std::string& path);
/// Builds a skeleton from parsed JSON; `file` names the source in error messages.
Skeleton parseSkeleton(const nlohmann::json& json, const std::string& file);

}  // namespace nenrin
