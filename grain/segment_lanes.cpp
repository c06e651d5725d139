#include "grain/segment_lanes.h"

#include <cmath>
#include <limits>

#include "util/simd_clones.h"

namespace nenrin {

// A free function: GCC clones it for AVX2 (util/simd_clones.h); lanes are independent.
NENRIN_AVX2_CLONES void measureInsideSegment(const FieldSegment& s, std::span<const Vec3> points,
                                             SegmentLanes& out) {
    const size_t n = points.size();
    const Vec3* __restrict p = points.data();
    const double ax = s.a.x, ay = s.a.y, az = s.a.z;
    const double bx = s.ab.x, by = s.ab.y, bz = s.ab.z;
    const double inv = s.invLength2, birthA = s.birthA, birthDelta = s.birthDelta;
    for (size_t i = 0; i < n; ++i) {
        // project()'s tRaw, then segmentPathTime's axis point, Ta and distance.
        const double t = ((p[i].x - ax) * bx + (p[i].y - ay) * by + (p[i].z - az) * bz) * inv;
        const double nx = ax + bx * t, ny = ay + by * t, nz = az + bz * t;
        const double dx = p[i].x - nx, dy = p[i].y - ny, dz = p[i].z - nz;
        out.t[i] = t;
        out.ax[i] = nx;
        out.ay[i] = ny;
        out.az[i] = nz;
        out.Ta[i] = birthA + birthDelta * t;
        out.distance[i] = std::sqrt(dx * dx + dy * dy + dz * dz);
    }
}

namespace {

/// One segment's project() at lanes [0, n), and the running nearest: restrict-qualified
/// parameters, so the loop vectorises.
__attribute__((always_inline)) inline void nearerOfSegment(
    const FieldSegment& s, double which, size_t n, const double* __restrict px,
    const double* __restrict py, const double* __restrict pz, double* __restrict best2,
    double* __restrict bestTRaw, double* __restrict bestT, double* __restrict bestWhich) {
    const double ax = s.a.x, ay = s.a.y, az = s.a.z;
    const double bx = s.ab.x, by = s.ab.y, bz = s.ab.z, inv = s.invLength2;
    for (size_t i = 0; i < n; ++i) {
        const double tRaw = ((px[i] - ax) * bx + (py[i] - ay) * by + (pz[i] - az) * bz) * inv;
        // std::min(std::max(tRaw, 0.0), 1.0) as project() takes it, as selects.
        const double lower = tRaw < 0.0 ? 0.0 : tRaw;
        const double t = 1.0 < lower ? 1.0 : lower;
        const double dx = px[i] - (ax + bx * t), dy = py[i] - (ay + by * t),
                     dz = pz[i] - (az + bz * t);
        const double d2 = dx * dx + dy * dy + dz * dz;
        const bool nearer = d2 < best2[i];
        best2[i] = nearer ? d2 : best2[i];
        bestTRaw[i] = nearer ? tRaw : bestTRaw[i];
        bestT[i] = nearer ? t : bestT[i];
        bestWhich[i] = nearer ? which : bestWhich[i];
    }
}

}  // namespace

NENRIN_AVX2_CLONES void nearestOfSegments(std::span<const FieldSegment> segments,
                                          std::span<const uint32_t> ids, const PointLanes& points,
                                          size_t n, NearestLanes& out) {
    for (size_t i = 0; i < n; ++i) {
        out.distance2[i] = std::numeric_limits<double>::infinity();
        out.tRaw[i] = out.t[i] = out.which[i] = 0;
    }
    for (size_t k = 0; k < ids.size(); ++k)
        nearerOfSegment(segments[ids[k]], double(k), n, points.x.data(), points.y.data(),
                        points.z.data(), out.distance2.data(), out.tRaw.data(), out.t.data(),
                        out.which.data());
}

}  // namespace nenrin
