#include "grain/branch_lanes.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "grain/field_bounds.h"
#include "util/simd_clones.h"

namespace nenrin {

namespace {

/// Four lanes of doubles and the masks their comparisons give (GCC's vector extensions: one
/// AVX2 register, or two SSE2 ones).
using Four = double __attribute__((vector_size(32)));
using Mask = long long __attribute__((vector_size(32)));

/// (By reference: a vector passed by value has another calling convention without AVX.)
inline const Four& load(const double* p, Four& v) {
    std::memcpy(&v, p, sizeof v);
    return v;
}
inline void store(double* p, const Four& v) { std::memcpy(p, &v, sizeof v); }
inline bool any(const Mask& m) { return (m[0] | m[1] | m[2] | m[3]) != 0; }
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

/// What the lanes read of a kept segment and its neighbours. Flags and the dieback power are
/// doubles (0 or 1; a small whole number) so that every field goes into lanes alike.
struct SegmentConstants {
    double ax, ay, az, bx, by, bz, birthA, birthDelta, inverseSpeed, deathTime;
    double birthBound, gammaBound, deathBound;
    double power;        ///< diebackPower of the smallest dieback exponent
    double boundMortal;  ///< 1 if deathBound is finite
    double mortal;       ///< 1 if deathTime is finite
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

/// What holds for every kept segment of the chain, or for some (a chain's segments mostly
/// agree: then a lane need not test its own).
struct ChainFlags {
    bool anyBoundMortal = false, allBoundMortal = true, anyMortal = false, allMortal = true;
    int maxPower = 0;  ///< the largest dieback power
    void add(const SegmentConstants& c) {
        anyBoundMortal |= c.boundMortal != 0, allBoundMortal &= c.boundMortal != 0;
        anyMortal |= c.mortal != 0, allMortal &= c.mortal != 0;
        maxPower = std::max(maxPower, static_cast<int>(c.power));
    }
};

/// Lanes [g, g + 4), each with its nearest kept segment: `lanes(&SegmentConstants::x, v)`
/// puts each lane's segment's x into v (read only as far as the lanes get).
template <class Lanes>
__attribute__((always_inline)) inline void laneGroup(Lanes lanes, const ChainFlags& flags,
                                                     const ReachBounds& bounds,
                                                     const BranchLaneInputs& in, size_t g,
                                                     BranchLanes& out) {
    using S = SegmentConstants;
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
    Four birthBound;
    lanes(&S::birthBound, birthBound);
    Mask keep = passes & ~(d2 > radius2) & ~(birthBound >= needed);
    // No term in any lane: only the state is read.
    if (!any(keep)) return store(&out.state[g], zero);
    Four gammaBound;
    lanes(&S::gammaBound, gammaBound);
    const Four gs = gammaBound * bounds.speedBound;
    Mask mortalKeep = keep, livingKeep = keep;
    if (flags.anyBoundMortal) {
        // diebackLowerBound (grain/field_bounds.h), each lane to its own segment's power.
        Four root, deathBound, power;
        lanes(&S::deathBound, deathBound), lanes(&S::power, power);
        squareRoot(d2, root);
        const Four bound = birthBound + root / gs;
        const Four x = bound / deathBound;
        Four factor = one;
        for (int n = 0; n < flags.maxPower; ++n) factor = double(n) < power ? factor * x : factor;
        const Four lower = bound > deathBound ? bound * factor : bound;
        mortalKeep &= ~(lower >= needed);
    }
    if (!flags.allBoundMortal) {
        const Four reachable = gs * (needed - birthBound);
        livingKeep &= ~(d2 >= reachable * reachable);
    }
    if (flags.allBoundMortal) {
        keep = mortalKeep;
    } else if (!flags.anyBoundMortal) {
        keep = livingKeep;
    } else {
        Four boundMortal;
        lanes(&S::boundMortal, boundMortal);
        keep = boundMortal != 0.0 ? mortalKeep : livingKeep;
    }
    if (!any(keep)) return store(&out.state[g], zero);
    // The path (grain/path_time.h: chainPathTime with no blend is segmentPathTime at t,
    // which inside the slab is tRaw).
    Four ax, ay, az, bx, by, bz, birthA, birthDelta, inverseSpeed, deathTime;
    lanes(&S::ax, ax), lanes(&S::ay, ay), lanes(&S::az, az);
    lanes(&S::bx, bx), lanes(&S::by, by), lanes(&S::bz, bz);
    lanes(&S::birthA, birthA), lanes(&S::birthDelta, birthDelta);
    lanes(&S::inverseSpeed, inverseSpeed), lanes(&S::deathTime, deathTime);
    const Four nx = ax + bx * u, ny = ay + by * u, nz = az + bz * u;
    const Four dx = px - nx, dy = py - ny, dz = pz - nz;
    Four distance;
    squareRoot(dx * dx + dy * dy + dz * dz, distance);
    const Four Ta = birthA + birthDelta * u;
    const Four Tb = distance * inverseSpeed;
    const Four T = Ta + Tb;
    Four pax, pay, paz, pbx, pby, pbz, pinv, nax, nay, naz, nbx, nby, nbz, ninv;
    lanes(&S::pax, pax), lanes(&S::pay, pay), lanes(&S::paz, paz);
    lanes(&S::pbx, pbx), lanes(&S::pby, pby), lanes(&S::pbz, pbz), lanes(&S::pinv, pinv);
    lanes(&S::nax, nax), lanes(&S::nay, nay), lanes(&S::naz, naz);
    lanes(&S::nbx, nbx), lanes(&S::nby, nby), lanes(&S::nbz, nbz), lanes(&S::ninv, ninv);
    const Four previousT = ((px - pax) * pbx + (py - pay) * pby + (pz - paz) * pbz) * pinv;
    const Four nextT = ((px - nax) * nbx + (py - nay) * nby + (pz - naz) * nbz) * ninv;
    const Mask blend =
        (tRaw >= 0.0) & (tRaw <= 1.0) &
        (((previousT >= 0.0) & (previousT <= 1.0)) | ((nextT >= 0.0) & (nextT <= 1.0)));
    // Branch segments only here: eq. 10 applies past the death time.
    const Mask dying = T > deathTime;
    // The term (branch_pass.cpp): junctionReachWeight and the encased-knot share.
    const Four floor = t1 < 1e-9 ? zero + 1e-9 : t1;
    Four share, dead = zero;
    smoothstep4(zero + 0.5, zero + 1.0, T / sinAlpha / (bounds.reach * floor), share);
    const Four weight = 1.0 - share;
    if (flags.anyMortal) {
        smoothstep4(deathTime - 0.5, deathTime + 0.5, t1, dead);
        if (!flags.allMortal) {
            Four mortal;
            lanes(&S::mortal, mortal);
            dead = mortal != 0.0 ? dead : zero;
        }
    }
    const Four term = weight <= 0.0 ? zero : one;
    store(&out.state[g], keep ? (blend ? zero + 3 : (dying ? zero + 2 : term)) : zero);
    store(&out.T[g], T);
    store(&out.Ta[g], Ta);
    store(&out.Tb[g], Tb);
    store(&out.distance[g], distance);
    store(&out.ax[g], nx);
    store(&out.ay[g], ny);
    store(&out.az[g], nz);
    store(&out.weight[g], weight);
    store(&out.dead[g], dead);
}

}  // namespace

// A free function: GCC clones it for AVX2 (util/simd_clones.h); lanes are independent.
NENRIN_AVX2_CLONES void branchLanes(const ReachBounds& bounds, const BranchLaneInputs& in,
                                    BranchLanes& out) {
    assert(in.ids.size() <= kBranchLaneSegments);
    std::array<SegmentConstants, kBranchLaneSegments> segments;
    ChainFlags flags;
    for (size_t k = 0; k < in.ids.size(); ++k) {
        segments[k] = constantsOf(bounds.segments, in.ids[k]);
        flags.add(segments[k]);
    }
    // Lanes past n (to the next multiple of 4) compute what is not used. Groups of four lanes
    // sharing one nearest segment (most, where points are dense along the branch) are taken
    // segment by segment with its constants in every lane; the others with each lane's own.
    const size_t lanes = (in.n + 3) / 4 * 4;
    auto shareOne = [&](const SegmentConstants& c, size_t g) __attribute__((always_inline)) {
        laneGroup(
            [&](double SegmentConstants::*x, Four& v) {
                const double one = c.*x;
                v = Four{one, one, one, one};
            },
            flags, bounds, in, g, out);
    };
    if (in.ids.size() == 1) {
        for (size_t g = 0; g < lanes; g += 4) shareOne(segments[0], g);
        return;
    }
    std::array<std::array<uint8_t, kLanes / 4>, kBranchLaneSegments> shared;
    std::array<uint8_t, kBranchLaneSegments> sharedCount{};
    std::array<uint8_t, kLanes / 4> mixed;
    size_t mixedCount = 0;
    for (size_t g = 0; g < lanes; g += 4) {
        const double* w = &in.nearest.which[g];
        const auto k = static_cast<size_t>(w[0]);
        if (w[1] == w[0] && w[2] == w[0] && w[3] == w[0])
            shared[k][sharedCount[k]++] = static_cast<uint8_t>(g / 4);
        else
            mixed[mixedCount++] = static_cast<uint8_t>(g / 4);
    }
    for (size_t k = 0; k < in.ids.size(); ++k)
        for (size_t j = 0; j < sharedCount[k]; ++j) shareOne(segments[k], size_t{shared[k][j]} * 4);
    for (size_t j = 0; j < mixedCount; ++j) {
        const size_t g = size_t{mixed[j]} * 4;
        const double* w = &in.nearest.which[g];
        const SegmentConstants &s0 = segments[static_cast<size_t>(w[0])],
                               &s1 = segments[static_cast<size_t>(w[1])],
                               &s2 = segments[static_cast<size_t>(w[2])],
                               &s3 = segments[static_cast<size_t>(w[3])];
        laneGroup(
            [&](double SegmentConstants::*x, Four& v) {
                v = Four{s0.*x, s1.*x, s2.*x, s3.*x};
            },
            flags, bounds, in, g, out);
    }
}

}  // namespace nenrin
