#pragma once
/// Four compact groups of a chunk's points, each with its bounding box: a squarish chunk is
/// cut at the middles of its two longest sides, a long one (second side under half the
/// first) into four along its length. A finely divided branch meets a quarter of a tile in
/// about half the segments it meets in the whole tile, so each point measures fewer.
/// The split is done on demand, once per chunk: only chains meeting the chunk in many
/// segments need it.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "grain/point_box.h"

namespace nenrin {

class PointQuarters {
public:
    /// A new chunk, not split yet: every point is in quarter 0. `boxLo`, `boxHi`: the points'
    /// bounding box. The points must outlive the use.
    void reset(std::span<const Vec3> points, const Vec3& boxLo, const Vec3& boxHi);
    /// Splits the chunk; later calls until the next reset() do nothing.
    void split();

    uint8_t quarterOf(size_t point) const { return split_ ? quarterOf_[point] : 0; }
    const Vec3& lo(int quarter) const { return boxes_[quarter].lo; }  ///< bounds of its points
    const Vec3& hi(int quarter) const { return boxes_[quarter].hi; }
    bool used(int quarter) const { return !boxes_[quarter].empty(); }  ///< false: no point in it

private:
    std::span<const Vec3> points_;
    Vec3 boxLo_, boxHi_;
    bool split_ = false;
    std::vector<uint8_t> quarterOf_;
    std::array<PointBox, 4> boxes_;
};

}  // namespace nenrin
