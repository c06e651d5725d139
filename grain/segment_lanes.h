#pragma once
/// One segment's path geometry (segmentPathTime's first half: the nearest axis point, the
/// elongation time Ta there and the distance to it) for a run of points at once, written over
/// arrays so that it vectorises. Every lane computes what segmentPathTime computes for its
/// point, in the same order: the same bits.

#include <array>
#include <cstddef>
#include <span>

#include "grain/field_segment.h"

namespace nenrin {

/// Points per run at most: a chunk (field_passes.h's kChunk); a multiple of 4.
inline constexpr size_t kLanes = 64;

/// A chunk's points, coordinate by coordinate, padded with zeros to a multiple of 4 (loops
/// of four lanes at a time read them; what they compute there is not used).
struct PointLanes {
    std::array<double, kLanes> x, y, z;
    void fill(std::span<const Vec3> points) {
        const size_t n = points.size();
        for (size_t i = 0; i < n; ++i) {
            x[i] = points[i].x;
            y[i] = points[i].y;
            z[i] = points[i].z;
        }
        pad(n);
    }
    /// Zeros from lane n to the next multiple of 4.
    void pad(size_t n) {
        for (size_t i = n; i < (n + 3) / 4 * 4; ++i) x[i] = y[i] = z[i] = 0;
    }
};

struct SegmentLanes {
    std::array<double, kLanes> t;           ///< position along the segment, as given (unclamped)
    std::array<double, kLanes> ax, ay, az;  ///< the axis point a + ab t
    std::array<double, kLanes> Ta;          ///< eq. 2 there
    std::array<double, kLanes> distance;    ///< from the point to the axis point
};

/// Fills lanes [0, points.size()) for points whose t along `s` is tRaw (they lie inside its
/// slab, where the path needs no joint blend). At most kLanes points.
void measureInsideSegment(const FieldSegment& s, std::span<const Vec3> points, SegmentLanes& out);

/// Per point, the nearest of some segments and its projection (project()'s answer), found by
/// one vectorised loop over the points per segment; ties go to the earlier segment, as a
/// scan with `<` gives them.
struct NearestLanes {
    std::array<double, kLanes> distance2, tRaw, t;
    std::array<double, kLanes> which;  ///< index into the segments given (a double: one lane type)
};
/// For the first n points of `points` and the segments `ids` of `segments` (in that order).
void nearestOfSegments(std::span<const FieldSegment> segments, std::span<const uint32_t> ids,
                       const PointLanes& points, size_t n, NearestLanes& out);

}  // namespace nenrin
