#include "grain/branch_lanes.h"

#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>

#include "grain/field_bounds.h"
#include "util/simd_clones.h"

namespace nenrin {

namespace {

/// Four lanes of doubles and the masks their comparisons give (GCC's vector extensions: one
/// AVX2 register, or two SSE2 ones). Written with them because each lane's segment is one of
/// a few: the loop runs once per segment over the groups of four lanes that hold it, with the
/// segment's fields as scalars, instead of loading them lane by lane.
using Four = double __attribute__((vector_size(32)));
using Mask = long long __attribute__((vector_size(32)));

/// (By reference: a vector passed by value has another calling convention without AVX.)
inline const Four& load(const double* p, Four& v) {
    std::memcpy(&v, p, sizeof v);
    return v;
}
inline void store(double* p, const Four& v) { std::memcpy(p, &v, sizeof v); }
/// Lanes of `v` where `m` is set, `old` elsewhere, stored at p.
__attribute__((always_inline)) inline void storeWhere(double* p, const Mask& m, bool all,
                                                      const Four& v) {
    if (all) return store(p, v);
    Four old;
    load(p, old);
    store(p, m ? v : old);
}
__attribute__((always_inline)) inline void squareRoot(const Four& v, Four& out) {
    out = Four{std::sqrt(v[0]), std::sqrt(v[1]), std::sqrt(v[2]), std::sqrt(v[3])};
}
/// smoothstep (grain/growth_terms.h) lane by lane: std::clamp's value for every input.
__attribute__((always_inline)) inline void smoothstep4(const Four& e0, const Four& e1,
                                                       const Four& x, Four& out) {
    const Four zero = {0, 0, 0, 0}, one = {1, 1, 1, 1};
    const Four v = (x - e0) / (e1 - e0);
    const Four high = one < v ? one : v;
    const Four t = v < zero ? zero : high;
    out = t * t * (3.0 - 2.0 * t);
}

/// What the lanes read of a kept segment and its neighbours (by value: the loop then reads
/// no memory that its stores could alias).
struct SegmentConstants {
    double ax, ay, az, bx, by, bz, birthA, birthDelta, inverseSpeed, deathTime;
    double birthBound, gammaBound, deathBound;
    int power;  ///< diebackPower of the smallest dieback exponent
    bool boundMortal, mortal;
    /// The previous and the next segment's a, ab and 1 / |ab|^2 (NaN where there is none:
    /// no point is then in its slab).
    double pax, pay, paz, pbx, pby, pbz, pinv;
    double nax, nay, naz, nbx, nby, nbz, ninv;
};

SegmentConstants constantsOf(std::span<const FieldSegment> segments, uint32_t id) {
    const FieldSegment& s = segments[id];
    assert(s.branch);  // eq. 10 is applied past deathTime without asking
    SegmentConstants c{};
    c.ax = s.a.x, c.ay = s.a.y, c.az = s.a.z, c.bx = s.ab.x, c.by = s.ab.y, c.bz = s.ab.z;
    c.birthA = s.birthA, c.birthDelta = s.birthDelta, c.inverseSpeed = s.inverseSpeed;
    c.deathTime = s.deathTime, c.mortal = std::isfinite(s.deathTime);
    c.birthBound = s.birthBound, c.gammaBound = s.gammaBound, c.deathBound = s.deathBound;
    c.power = diebackPower(s.diebackBound), c.boundMortal = std::isfinite(s.deathBound);
    auto neighbour = [&](int32_t n, double& ax, double& ay, double& az, double& bx, double& by,
                         double& bz, double& inv) {
        if (n == kNone) {
            inv = std::numeric_limits<double>::quiet_NaN();
            return;
        }
        const FieldSegment& x = segments[static_cast<uint32_t>(n)];
        ax = x.a.x, ay = x.a.y, az = x.a.z, bx = x.ab.x, by = x.ab.y, bz = x.ab.z;
        inv = x.invLength2;
    };
    neighbour(s.previous, c.pax, c.pay, c.paz, c.pbx, c.pby, c.pbz, c.pinv);
    neighbour(s.next, c.nax, c.nay, c.naz, c.nbx, c.nby, c.nbz, c.ninv);
    return c;
}

/// Lanes [g, g + 4) where `mask` is set: their nearest kept segment is c's.
__attribute__((always_inline)) inline void laneGroup(const SegmentConstants& c,
                                                     const ReachBounds& bounds,
                                                     const BranchLaneInputs& in, size_t g,
                                                     const Mask& mask, BranchLanes& out) {
    const Four zero = {0, 0, 0, 0}, one = {1, 1, 1, 1};
    Four px, py, pz, t1, sinAlpha, slack, radius2, outside2, d2, tRaw, u;
    load(&in.points.x[g], px), load(&in.points.y[g], py), load(&in.points.z[g], pz);
    load(&in.trunkTimes[g], t1), load(&in.reach.sinAlpha[g], sinAlpha);
    load(&in.reach.slack[g], slack), load(&in.reach.radius2[g], radius2);
    load(&in.reach.outside2[g], outside2);
    load(&in.nearest.distance2[g], d2), load(&in.nearest.tRaw[g], tRaw);
    load(&in.nearest.t[g], u);
    // ReachLanes::passes, then mayComeUnderReach (branch_pass.cpp); the age warp is off
    // (plain thickening), so ageWarp and ageUnwarp are the identity.
    const Mask passes = ~((sinAlpha <= 0.0) | (slack <= 0.0) | (outside2 > radius2));
    const Four needed = bounds.reach * t1 * sinAlpha;
    Mask keep = passes & ~(d2 > radius2) & ~(c.birthBound >= needed);
    const bool all = (mask[0] & mask[1] & mask[2] & mask[3]) != 0;
    // No term in any lane: only the state is read.
    auto none = [&] {
        const Mask taken = keep & mask;
        return (taken[0] | taken[1] | taken[2] | taken[3]) == 0;
    };
    if (none()) return storeWhere(&out.state[g], mask, all, zero);
    const double gs = c.gammaBound * bounds.speedBound;
    if (c.boundMortal) {
        // diebackLowerBound (grain/field_bounds.h).
        Four root;
        squareRoot(d2, root);
        const Four bound = c.birthBound + root / gs;
        const Four x = bound / c.deathBound;
        Four factor = one;
        for (int n = 0; n < c.power; ++n) factor *= x;
        const Four lower = bound > c.deathBound ? bound * factor : bound;
        keep &= ~(lower >= needed);
    } else {
        const Four reachable = gs * (needed - c.birthBound);
        keep &= ~(d2 >= reachable * reachable);
    }
    if (none()) return storeWhere(&out.state[g], mask, all, zero);
    // The path (grain/path_time.h: chainPathTime with no blend is segmentPathTime at t,
    // which inside the slab is tRaw).
    const Four nx = c.ax + c.bx * u, ny = c.ay + c.by * u, nz = c.az + c.bz * u;
    const Four dx = px - nx, dy = py - ny, dz = pz - nz;
    Four distance;
    squareRoot(dx * dx + dy * dy + dz * dz, distance);
    const Four Ta = c.birthA + c.birthDelta * u;
    const Four Tb = distance * c.inverseSpeed;
    const Four T = Ta + Tb;
    const Four previousT =
        ((px - c.pax) * c.pbx + (py - c.pay) * c.pby + (pz - c.paz) * c.pbz) * c.pinv;
    const Four nextT =
        ((px - c.nax) * c.nbx + (py - c.nay) * c.nby + (pz - c.naz) * c.nbz) * c.ninv;
    const Mask blend =
        (tRaw >= 0.0) & (tRaw <= 1.0) &
        (((previousT >= 0.0) & (previousT <= 1.0)) | ((nextT >= 0.0) & (nextT <= 1.0)));
    // Branch segments only here: eq. 10 applies past the death time.
    const Mask dying = T > c.deathTime;
    // The term (branch_pass.cpp): junctionReachWeight and the encased-knot share.
    const Four floor = t1 < 1e-9 ? zero + 1e-9 : t1;
    Four share, dead = zero;
    smoothstep4(zero + 0.5, zero + 1.0, T / sinAlpha / (bounds.reach * floor), share);
    const Four weight = 1.0 - share;
    if (c.mortal) smoothstep4(zero + (c.deathTime - 0.5), zero + (c.deathTime + 0.5), t1, dead);
    const Four term = weight <= 0.0 ? zero : one;
    const Four state = keep ? (blend ? zero + 3 : (dying ? zero + 2 : term)) : zero;
    storeWhere(&out.state[g], mask, all, state);
    storeWhere(&out.T[g], mask, all, T);
    storeWhere(&out.Ta[g], mask, all, Ta);
    storeWhere(&out.Tb[g], mask, all, Tb);
    storeWhere(&out.distance[g], mask, all, distance);
    storeWhere(&out.ax[g], mask, all, nx);
    storeWhere(&out.ay[g], mask, all, ny);
    storeWhere(&out.az[g], mask, all, nz);
    storeWhere(&out.weight[g], mask, all, weight);
    storeWhere(&out.dead[g], mask, all, dead);
}

}  // namespace

// A free function: GCC clones it for AVX2 (util/simd_clones.h); lanes are independent.
NENRIN_AVX2_CLONES void branchLanes(const ReachBounds& bounds, const BranchLaneInputs& in,
                                    BranchLanes& out) {
    // Lanes past n (to the next multiple of 4) compute what is not used.
    const size_t lanes = (in.n + 3) / 4 * 4;
    for (size_t k = 0; k < in.ids.size(); ++k) {
        const SegmentConstants c = constantsOf(bounds.segments, in.ids[k]);
        const double which = static_cast<double>(k);
        for (size_t g = 0; g < lanes; g += 4) {
            Four w;
            const Mask mask = load(&in.nearest.which[g], w) == which;
            if (!(mask[0] | mask[1] | mask[2] | mask[3])) continue;
            laneGroup(c, bounds, in, g, mask, out);
        }
    }
}

}  // namespace nenrin
