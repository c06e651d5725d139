#pragma once
/// Four compact groups of a chunk's points, each with its bounding box: a squarish chunk is
/// cut at the middles of its two longest sides, a long one (second side under half the
/// first) into four along its length. A finely divided branch meets a quarter of a tile in
/// about half the segments it meets in the whole tile, so each point measures fewer.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "util/vec3.h"

namespace nenrin {

struct PointQuarters {
    std::vector<uint8_t> quarterOf;  ///< per point of the chunk: 0..3
    std::array<Vec3, 4> lo, hi;      ///< bounds of each quarter's points
    std::array<bool, 4> used{};      ///< false: no point fell in that quarter

    /// `boxLo`, `boxHi`: the points' bounding box.
    void split(std::span<const Vec3> points, const Vec3& boxLo, const Vec3& boxHi);
};

}  // namespace nenrin
