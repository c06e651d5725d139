#pragma once
/// A skeleton segment flattened for the growth field's inner loops: everything one path-time
/// evaluation reads, in one place, with the divisions done once.

#include <algorithm>
#include <vector>

#include "skeleton/segment_geometry.h"
#include "skeleton/skeleton.h"

namespace nenrin {

/// Aligned to cache lines, with what project() reads (a, ab, 1 / L^2) in the first: the
/// nearest-segment scans touch one line per segment.
struct alignas(64) FieldSegment {
    Vec3 a, ab;             ///< start and (end - start)
    double invLength2 = 0;  ///< 1 / |ab|^2
    double length = 0;
    Vec3 axis;                          ///< unit direction
    double birthA = 0, birthDelta = 0;  ///< birth time at a, and at b minus at a
    double gamma = 1, deathTime = kNeverDies, diebackExponent = 0;
    double inverseSpeed = 0;  ///< 1 / (Sb gamma), years per metre (set by GrowthField)
    /// Bounds over this segment and its chain neighbours (all that its joint blend can use),
    /// chosen so that a time computed from them is a lower bound of the path time: the
    /// smallest node birth time, the largest gamma, the latest death and the smallest
    /// dieback exponent.
    double birthBound = 0, gammaBound = 1, deathBound = kNeverDies, diebackBound = 0;
    int32_t previous = kNone, next = kNone;
    uint32_t chain = 0;
    bool branch = false;
};

inline SegmentProjection project(const FieldSegment& s, const Vec3& p) {
    double tRaw = dot(p - s.a, s.ab) * s.invLength2;
    // std::clamp's value for every input (NaN and -0 included), as min/max instructions: a
    // branch here is mispredicted on every other segment a point measures.
    double t = std::min(std::max(tRaw, 0.0), 1.0);
    Vec3 d = p - (s.a + s.ab * t);
    return {tRaw, t, dot(d, d)};
}

inline std::vector<FieldSegment> flattenSegments(const Skeleton& sk) {
    std::vector<FieldSegment> out;
    out.reserve(sk.segments().size());
    for (const auto& s : sk.segments()) {
        FieldSegment f;
        f.a = sk.start(s);
        f.ab = sk.end(s) - f.a;
        f.length = length(f.ab);
        f.axis = f.ab / f.length;
        f.invLength2 = 1 / (f.length * f.length);
        f.birthA = sk.node(s.from).birthTime;
        f.birthDelta = sk.node(s.to).birthTime - f.birthA;
        f.gamma = s.gamma;
        f.deathTime = s.deathTime;
        f.diebackExponent = s.diebackExponent;
        f.previous = s.previous;
        f.next = s.next;
        f.chain = s.chain;
        f.branch = s.kind == SegmentKind::Branch;
        out.push_back(f);
    }
    for (auto& f : out) {
        f.birthBound = std::min(f.birthA, f.birthA + f.birthDelta);
        f.gammaBound = f.gamma;
        f.deathBound = f.branch ? f.deathTime : kNeverDies;
        f.diebackBound = f.diebackExponent;
        for (int32_t m : {f.previous, f.next}) {
            if (m == kNone) continue;
            const FieldSegment& x = out[static_cast<size_t>(m)];
            f.birthBound = std::min({f.birthBound, x.birthA, x.birthA + x.birthDelta});
            f.gammaBound = std::max(f.gammaBound, x.gamma);
            f.deathBound = std::max(f.deathBound, x.branch ? x.deathTime : kNeverDies);
            f.diebackBound = std::min(f.diebackBound, x.diebackExponent);
        }
    }
    return out;
}

}  // namespace nenrin
