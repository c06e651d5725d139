#include "grain/reach_lanes.h"

#include <algorithm>
#include <cmath>

#include "grain/growth_terms.h"
#include "util/simd_clones.h"

namespace nenrin {

namespace {

/// max(max(lo - x, x - hi), 0) as std::max computes it, written as selects of values.
inline double outsideBy(double lo, double hi, double x) {
    const double below = lo - x, above = x - hi;
    const double m = below < above ? above : below;
    return m < 0.0 ? 0.0 : m;
}

/// What the tests read of one tile chain and the field, by value (so the loop reads no memory
/// that its stores could alias).
struct ChainConstants {
    double sx, sy, sz;  ///< Q
    double fx, fy, fz;  ///< normal of plane F
    double scale, reach, birth, delta;
    double lx, ly, lz, ux, uy, uz;  ///< the kept segments' box
};

/// The tests for lanes [0, n); `kWarp`: the age warp is on (a pow per lane: not vectorised).
/// Restrict-qualified parameters: the arrays do not overlap, so the loop vectorises.
template <bool kWarp>
__attribute__((always_inline)) inline void reachLoop(
    const ChainConstants c, size_t n, const double* __restrict px, const double* __restrict py,
    const double* __restrict pz, const double* __restrict trunkTimes,
    double* __restrict sinAlphaOut, double* __restrict slackOut, double* __restrict radius2Out,
    double* __restrict outside2Out) {
    for (size_t i = 0; i < n; ++i) {
        // alpha: angle between QP and the plane F through the branch start Q, perpendicular
        // to the branch (eq. 5). Behind F the branch does not count.
        const double vx = px[i] - c.sx, vy = py[i] - c.sy, vz = pz[i] - c.sz;
        const double lv = std::sqrt(vx * vx + vy * vy + vz * vz);
        const double along = vx * c.fx + vy * c.fy + vz * c.fz;
        // (The division is done in every lane, by 1 where lv is 0, so the loop has no branch.)
        const double quotient = along / (lv > 0 ? lv : 1);
        const double sinAlpha = lv > 0 ? quotient : 0;
        // Beyond this distance T_c / sin(alpha) is past reach x T1: weight 0.
        const double slack = c.reach * trunkTimes[i] * sinAlpha - c.birth;
        const double radius = c.scale * (kWarp ? ageUnwarp(slack, c.delta) : slack);
        // The box around the chain's kept segments out of reach.
        const double ox = outsideBy(c.lx, c.ux, px[i]);
        const double oy = outsideBy(c.ly, c.uy, py[i]);
        const double oz = outsideBy(c.lz, c.uz, pz[i]);
        sinAlphaOut[i] = sinAlpha;
        slackOut[i] = slack;
        radius2Out[i] = radius * radius;
        outside2Out[i] = ox * ox + oy * oy + oz * oz;
    }
}

}  // namespace

NENRIN_AVX2_CLONES void reachTests(const TileChain& chain, const ReachBounds& bounds,
                                   const PointLanes& points, size_t n, const double* trunkTimes,
                                   ReachLanes& out) {
    const ChainConstants c{chain.start.x,
                           chain.start.y,
                           chain.start.z,
                           chain.direction.x,
                           chain.direction.y,
                           chain.direction.z,
                           chain.gamma * bounds.speedBound,
                           bounds.reach,
                           chain.birthBound,
                           bounds.delta,
                           chain.lower.x,
                           chain.lower.y,
                           chain.lower.z,
                           chain.upper.x,
                           chain.upper.y,
                           chain.upper.z};
    if (bounds.delta == 1.0)
        reachLoop<false>(c, n, points.x.data(), points.y.data(), points.z.data(), trunkTimes,
                         out.sinAlpha.data(), out.slack.data(), out.radius2.data(),
                         out.outside2.data());
    else
        reachLoop<true>(c, n, points.x.data(), points.y.data(), points.z.data(), trunkTimes,
                        out.sinAlpha.data(), out.slack.data(), out.radius2.data(),
                        out.outside2.data());
}

}  // namespace nenrin
