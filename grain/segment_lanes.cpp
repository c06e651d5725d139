#include "grain/segment_lanes.h"

#include <cmath>
#include <cstring>
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

/// Four lanes of doubles (GCC's vector extension: one AVX2 register, or two SSE2 ones). The
/// running minimum below is written with them because GCC turns its plain-loop form into
/// conditional stores, which it then cannot vectorise.
using Four = double __attribute__((vector_size(32)));
/// (By reference: a vector passed by value has another calling convention without AVX.)
inline const Four& load(const double* p, Four& v) {
    std::memcpy(&v, p, sizeof v);
    return v;
}
inline void store(double* p, const Four& v) { std::memcpy(p, &v, sizeof v); }

/// One segment's project() at lanes [0, n rounded up to 4) (PointLanes pads them), and the
/// running nearest, lane by lane as the scalar code computes it. `kFirst`: the first segment,
/// measured against a nearest at infinity (not read from `out`: the lanes are not set yet).
template <bool kFirst>
inline void nearerOfSegment(const FieldSegment& s, double which, size_t n, const PointLanes& p,
                            NearestLanes& out) {
    const double ax = s.a.x, ay = s.a.y, az = s.a.z;
    const double bx = s.ab.x, by = s.ab.y, bz = s.ab.z, inv = s.invLength2;
    const Four zero = {0, 0, 0, 0}, one = {1, 1, 1, 1}, index = zero + which;
    for (size_t i = 0; i < n; i += 4) {
        Four x, y, z, best, oldTRaw, oldT, oldWhich;
        load(&p.x[i], x);
        load(&p.y[i], y);
        load(&p.z[i], z);
        const Four tRaw = ((x - ax) * bx + (y - ay) * by + (z - az) * bz) * inv;
        // std::min(std::max(tRaw, 0.0), 1.0) as project() takes it.
        const Four lower = tRaw < zero ? zero : tRaw;
        const Four t = one < lower ? one : lower;
        const Four dx = x - (ax + bx * t), dy = y - (ay + by * t), dz = z - (az + bz * t);
        const Four d2 = dx * dx + dy * dy + dz * dz;
        if constexpr (kFirst) {
            const Four infinity = zero + std::numeric_limits<double>::infinity();
            const auto nearer = d2 < infinity;
            store(&out.distance2[i], nearer ? d2 : infinity);
            store(&out.tRaw[i], nearer ? tRaw : zero);
            store(&out.t[i], nearer ? t : zero);
            store(&out.which[i], nearer ? index : zero);
            continue;
        }
        const auto nearer = d2 < load(&out.distance2[i], best);
        store(&out.distance2[i], nearer ? d2 : best);
        store(&out.tRaw[i], nearer ? tRaw : load(&out.tRaw[i], oldTRaw));
        store(&out.t[i], nearer ? t : load(&out.t[i], oldT));
        store(&out.which[i], nearer ? index : load(&out.which[i], oldWhich));
    }
}

}  // namespace

NENRIN_AVX2_CLONES void nearestOfSegments(std::span<const FieldSegment> segments,
                                          std::span<const uint32_t> ids, const PointLanes& points,
                                          size_t n, NearestLanes& out) {
    const size_t lanes = (n + 3) / 4 * 4;
    if (ids.empty()) {
        for (size_t i = 0; i < lanes; ++i) {
            out.distance2[i] = std::numeric_limits<double>::infinity();
            out.tRaw[i] = out.t[i] = out.which[i] = 0;
        }
        return;
    }
    nearerOfSegment<true>(segments[ids[0]], 0, lanes, points, out);
    for (size_t k = 1; k < ids.size(); ++k)
        nearerOfSegment<false>(segments[ids[k]], double(k), lanes, points, out);
}

}  // namespace nenrin
