#include "grain/knot_look.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "grain/growth_terms.h"
#include "util/axis_frame.h"
#include "util/hash.h"
#include "util/value_noise.h"

namespace nenrin {

namespace {

/// The halo's patches: a value noise on a lattice of 1.5 halo widths varies its reach by half.
constexpr double kHaloNoiseScale = 1.5, kHaloPatchiness = 0.5;
constexpr uint64_t kHaloSalt = 0x4a10;
/// The knot share under which the halo fades out with the branch's term.
constexpr double kHaloShareFade = 0.1;
/// The knots' ring wobble's own noise, apart from the halo's.
constexpr uint64_t kWobbleSalt = 0x4a11;

/// The knot tint's weight: how far P is inside the knot by the branch's share.
double insideKnot(const GrowthSample& s) { return smoothstep(0.45, 0.75, s.knot); }

/// A radial drying check of a dead knot: a crack in the plane through the branch's axis at
/// the knot's own seeded azimuth, opening from the pith outward and closing at the bark.
double checkCoverage(const GrowthSample& s, const ColourParams& c, double u, double footprint) {
    if (c.deadKnotChecks <= 0 || s.knotChain < 0 || u >= 1) return 0;
    const uint64_t chain = static_cast<uint64_t>(s.knotChain);
    if (uniform01(c.microSeed, chain, 1) >= c.deadKnotChecks) return 0;
    const Vec3 a = normalize(s.knotAxisDirection);
    const AxisFrame frame(a);
    const Vec3 &e1 = frame.s, &e2 = frame.t;
    const double phi0 = 2 * std::numbers::pi * uniform01(c.microSeed, chain, 2);
    const Vec3 crack = e1 * std::cos(phi0) + e2 * std::sin(phi0);
    const Vec3 across = cross(a, crack);
    const Vec3& offset = s.knotOffset;
    if (dot(offset, crack) <= 0) return 0;  // one check, on one side of the pith
    const double width =
        c.deadKnotCheckWidth * std::min(1.0, u / 0.3) * (1 - smoothstep(0.8, 1.0, u));
    const double side = dot(offset, across);
    return boxCoverage(side, -0.5 * width, 0.5 * width, footprint);
}

}  // namespace

KnotLook knotLook(const GrowthSample& s, const ColourParams& c, double footprint) {
    KnotLook out;
    if (s.knot <= 0) return out;
    // Darkening follows the knot share; how much of it is the dead-knot kind follows the
    // fraction of the knot that is dead, so the live/dead change along a branch (where the
    // trunk reached it after its death) shifts the tone without drawing an edge.
    const double inside = insideKnot(s);
    out.deadFraction = std::clamp(s.deadKnot / s.knot, 0.0, 1.0);
    out.tint = inside;
    // Where in the knot's section P lies: 0 at its pith, 1 at its edge (or a dead one's bark).
    const double u = s.knotRadius > 0 ? s.knotAxisDistance / s.knotRadius : 1.0;
    const double core = c.knotCore * (1 - smoothstep(0.0, 1.0, u));
    double darkening =
        inside * (mix(c.knotDarkening, c.deadKnotDarkening, out.deadFraction) + core);
    // The bark of a dead branch, encased by the trunk: a band just inside the knot's edge,
    // the same width all round.
    if (s.knotDied && s.knotRadius > 0) {
        out.rim = out.deadFraction *
                  boxCoverage(s.knotAxisDistance - s.knotRadius, -c.deadKnotRimWidth, 0, footprint);
        out.check = out.deadFraction * inside * checkCoverage(s, c, u, footprint);
    }
    darkening = 1 - (1 - darkening) * (1 - c.deadKnotRim * out.rim) * (1 - 0.8 * out.check);
    out.darkening = std::clamp(darkening, 0.0, 0.95);
    return out;
}

double knotHalo(const GrowthSample& s, const Vec3& treePoint, const ColourParams& c) {
    if (s.knotChain < 0 || c.knotHaloWidth <= 0 || s.knotRadius <= 0) return 0;
    // Where the branch's term leaves the junction's reach the field names no chain: faded out
    // with its share there, or the halo would end in a drawn edge (a dead knot's term, its
    // time raised by dieback, leaves it a few millimetres out).
    const double fade = smoothstep(0.0, kHaloShareFade, s.knot);
    const double d = s.knotAxisDistance;
    if (d <= s.knotRadius) return fade;
    // An ellipse about the branch's axis, stretched along the stem's as seen in the branch's
    // cross-section (the stem's direction less its part along the branch, so that a slanting
    // branch's halo is stretched as much): on this ray the halo reaches width x d / stretched
    // beyond the knot's edge.
    const Vec3 branch = normalize(s.knotAxisDirection);
    const Vec3 stem = normalize(s.axisDirection - branch * dot(s.axisDirection, branch));
    const double along = dot(s.knotOffset, stem);
    const double across2 = std::max(0.0, d * d - along * along);
    const double stretched =
        std::sqrt(across2 + along * along / (c.knotHaloAxial * c.knotHaloAxial));
    const Vec3 q = treePoint * (1 / (kHaloNoiseScale * c.knotHaloWidth));
    const double patch =
        1 + kHaloPatchiness * valueNoise(hashCombine(c.microSeed, kHaloSalt), q.x, q.y, q.z);
    const double reach = patch * c.knotHaloWidth * d / std::max(stretched, 1e-12 * d);
    return (1 - smoothstep(0.0, 1.0, (d - s.knotRadius) / reach)) * fade;
}

double knotRingWobble(const GrowthSample& s, const Vec3& treePoint, const ColourParams& c) {
    if (c.knotRingWobble <= 0 || s.knot <= 0) return 0;
    const double inside = insideKnot(s);
    if (inside <= 0) return 0;
    const Vec3 q = treePoint * (1 / c.knotRingWobbleScale);
    const uint64_t seed = hashCombine(c.microSeed, kWobbleSalt);
    // Two octaves, the finer half as strong: one alone draws smooth, regular bulges.
    const double n =
        (valueNoise(seed, q.x, q.y, q.z) + 0.5 * valueNoise(seed + 1, 2 * q.x, 2 * q.y, 2 * q.z)) /
        1.5;
    return inside * c.knotRingWobble * n;
}

}  // namespace nenrin
