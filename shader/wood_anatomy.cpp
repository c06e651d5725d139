#include "shader/wood_anatomy.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

#include "grain/growth_terms.h"
#include "util/axis_frame.h"
#include "util/hash.h"
#include "util/value_noise.h"

namespace nenrin {

namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

/// 1 while the footprint is below `from` of the feature's cell, 0 from `from` + 0.75 cells on:
/// past that, the filtered feature is replaced by its mean (neighbours would enter the box).
/// Tubes, whose filtered coverage keeps its mean and takes the neighbouring cells in, keep
/// their detail up to half a cell (from 0.5); the other features up to a quarter.
double detail(double footprint, double cell, double from = 0.25) {
    return 1 - std::clamp((footprint / cell - from) / 0.75, 0.0, 1.0);
}

/// Near a pith (the trunk's, or a branch's inside its knot) the base ray count would crowd
/// the rays together: there ray j of the base level only runs from its start radius on. The
/// rays whose index has t trailing zero bits start near kRaysComplete 2^-t (jittered by
/// +-25 %), so every other ray starts at half the radius of the next: the spacing stays near
/// 0.75-1.5 x the ray spacing at any radius, as new rays start where the circumference grows.
constexpr double kRaysComplete = 0.0375;  // m: 0.75 x the 5 cm at which the base count fits

double rayStart(long long j, uint64_t seed) {
    const int t = j == 0 ? 62 : std::countr_zero(static_cast<unsigned long long>(j));
    return kRaysComplete * std::ldexp(1.0, -t) * (0.75 + 0.5 * cellRandom(seed, 205, j, 0));
}

/// A ray's tangential wavering: amplitude in ray widths, wavelengths radially and axially (m).
constexpr double kRayWaver = 2;
constexpr double kRayWaverRadial = 0.012;
constexpr double kRayWaverAxial = 0.008;

/// Share of the base level's rays running at radius rho (the mean of rayStart's test).
double raysStarted(double rho) {
    double share = 0, weight = 0.5;
    for (int t = 0; t < 62; ++t, weight *= 0.5) {
        const double x = (rho / (kRaysComplete * std::ldexp(1.0, -t)) - 0.75) / 0.5;
        if (x >= 1) return share + 2 * weight;  // this and every later class: all started
        share += weight * std::max(0.0, x);
    }
    return share;
}

struct WoodFrame {
    double rho, theta, z, T, gradT;  // m, rad, m, years, years/m
    double ft, fr, fz;               // footprint extents along tangential, radial, axial (m)
    // Rings are not circles about the axis (sway, the sun side): a step `dt` along the circle
    // and `dr` in ring-aligned radial position (T / |grad T|) is a true radial step of
    // scale dr - shear dt.
    double scale = 1, shear = 0;
    Vec3 t, r;  // unit tangential and radial directions
};

/// A vessel is a continuous tube (its elements joined end to end), but not a straight one: it
/// wanders across the fibre by up to this many of its radii over a `wander` length. An end-grain
/// cut shows every vessel; a cut along the fibre passes in and out of them and shows dashes.
constexpr double kVesselWander = 1.2;

/// Tubes along the fibre, one in each cell of (tangential, radial) cells: an elliptic section
/// of half-size `half` around a jittered centre that wanders along the fibre over `wander` m.
/// `rows` > 0 limits the radial cells to rows 0 .. rows - 1 (a ring's band).
struct TubeCell {
    double tCell, rCell;  // m
    double wander;        // m
    double half;
    double probability;
    long long rows = 0;
};

/// Smooth noise in [-1, 1] along z for cell (it, ir): the cell's wander on one axis.
double wanderAlong(uint64_t seed, uint64_t salt, long long it, long long ir, double u) {
    const double k = std::floor(u), t = u - k;
    const double a = cellRandom(seed, salt, it, ir, (long long)k),
                 b = cellRandom(seed, salt, it, ir, (long long)k + 1);
    return 2 * (a + (b - a) * t * t * (3 - 2 * t)) - 1;
}

/// The vessel of cell (it, row) seen through a footprint of radius `rw` (a disc of the
/// footprint's area): its coverage at (tPos, rPos); `outward` gets the direction from its axis.
double vesselInCell(const WoodFrame& f, const TubeCell& c, double tPos, double rPos, long long it,
                    long long row, long long ring, double rw, uint64_t seed, uint64_t salt,
                    Vec3& outward) {
    const long long ir = row + ring * 1000003;
    if (cellRandom(seed, salt, it, ir) >= c.probability) return 0;
    // Each vessel its own size and slightly oval section, so they do not read as stamped.
    const double size = 0.7 + 0.6 * cellRandom(seed, salt + 5, it, ir);
    const double oval = 0.8 + 0.45 * cellRandom(seed, salt + 6, it, ir);
    const double half = c.half * size;
    const double mt = std::min(0.5, half / c.tCell + 0.02),
                 mr = std::min(0.5, half / c.rCell + 0.02);
    const double u = f.z / c.wander + 64 * cellRandom(seed, salt + 3, it, ir);
    const double ct = (it + mt + (1 - 2 * mt) * cellRandom(seed, salt + 1, it, ir)) * c.tCell +
                      kVesselWander * half * wanderAlong(seed, salt + 7, it, ir, u);
    const double cr = (row + mr + (1 - 2 * mr) * cellRandom(seed, salt + 2, it, ir)) * c.rCell +
                      kVesselWander * half * wanderAlong(seed, salt + 8, it, ir, u);
    // The section, an ellipse, box-filtered by the footprint: the disc of radius `half`
    // convolved with the footprint's disc is flat out to |half - rw| and falls to 0 at
    // half + rw; its height keeps the vessel's area, so a vessel smaller than a pixel still
    // darkens that pixel by its share instead of fading away (the edge stays 0.2 of the
    // radius wide at least: no aliasing stair-steps in a close-up).
    const double dt = tPos - ct, dr = f.scale * (rPos - cr) - f.shear * dt;
    const double n = std::hypot(dt / oval, dr * oval);
    const double soft = std::max(rw, 0.2 * half);
    const double a = std::abs(half - soft), b = half + soft;
    const double height = std::min(1.0, 3 * half * half / (a * a + a * b + b * b));
    const double section = height * std::clamp((b - n) / (b - a), 0.0, 1.0);
    if (section > 0) {
        const double l = std::hypot(dt, dr);
        outward = l > 0 ? (f.t * dt + f.r * dr) * (1 / l) : Vec3{};
    }
    return section;
}

/// What the tubes give at a point: their coverage, faded to its mean as the footprint grows
/// past half a cell, the slope factor of an open pore's pit, and the direction from the
/// strongest tube's axis.
struct TubeSample {
    double coverage = 0;
    double pit = 0;
    Vec3 outward;
};

/// The tubes at radial position rPos: the point's own cell and, where a vessel filtered by
/// the footprint could reach over the cell's edge, the neighbours on that side.
TubeSample tube(const WoodFrame& f, const TubeCell& c, double rPos, long long ring, uint64_t seed,
                uint64_t salt) {
    const double rw = std::max(f.ft, f.fr) * 0.5642;  // 1 / sqrt(pi): a disc of its area
    // How far past its cell's edge a vessel can reach: wander, the filter, the oval's slack.
    const double reach = rw + (kVesselWander + 0.3) * 1.3 * c.half;
    const double rowPos = rPos / c.rCell;
    const long long row = (long long)std::floor(rowPos);
    const double spill = reach / c.rCell;
    TubeSample out;
    double cov = 0, strongest = 0;
    for (long long r = row - (rowPos - row < spill); r <= row + (row + 1 - rowPos < spill); ++r) {
        if (c.rows > 0 && (r < 0 || r >= c.rows)) continue;
        // Along the row: arc length at the row's own middle radius, so the cells' sides are
        // rays and rings (at rho, rho * theta would shear them by theta, into slanted dashes).
        const double tPos = std::max(f.rho + (r + 0.5) * c.rCell - rPos, c.rCell) * f.theta;
        const double colPos = tPos / c.tCell;
        const long long col = (long long)std::floor(colPos);
        const double tSpill = reach / c.tCell;
        for (long long t = col - (colPos - col < tSpill); t <= col + (col + 1 - colPos < tSpill);
             ++t) {
            Vec3 direction;
            const double v = vesselInCell(f, c, tPos, rPos, t, r, ring, rw, seed, salt, direction);
            cov += v;
            if (v > strongest) strongest = v, out.outward = direction;
        }
    }
    cov = std::min(cov, 1.0);
    // pi/4 an ellipse in its box, sizes 0.7-1.3 (mean square 1.03): any cut through tubes
    // covers their share of the volume.
    const double mean =
        c.probability * 0.785 * 1.03 * (2 * c.half / c.tCell) * (2 * c.half / c.rCell);
    const double keep =
        std::min(detail(std::max(f.ft, f.fr), c.tCell, 0.5), detail(f.fz, c.wander, 0.5));
    out.coverage = keep * cov + (1 - keep) * mean;
    out.pit = keep * cov * (1 - cov) * 4;
    return out;
}

}  // namespace

AnatomySample woodAnatomy(const AnatomyParams& p, const GrowthSample& s, const Vec3& point,
                          const Vec3& gradT, const Vec3& dpdx, const Vec3& dpdy, double diameter,
                          double weight) {
    return woodAnatomy(p, {point - s.axisPoint, s.axisDirection}, s.T, point, gradT, dpdx, dpdy,
                       diameter, weight);
}

namespace {

/// The local wood frame about the axis at `point`; false on the axis itself.
bool woodFrameAt(const AnatomyAxis& axis, double T, const Vec3& point, const Vec3& gradT,
                 const Vec3& dpdx, const Vec3& dpdy, double diameter, WoodFrame& f) {
    const Vec3 a = normalize(axis.direction);
    const Vec3& d = axis.offset;
    const Vec3 perp = d - a * dot(d, a);
    f.rho = length(perp);
    if (f.rho < 1e-5) return false;
    const AxisFrame axisFrame(a);
    const Vec3 &e1 = axisFrame.s, &e2 = axisFrame.t;
    f.theta = std::atan2(dot(perp, e2), dot(perp, e1));
    f.z = dot(point, a);
    f.T = T;
    f.gradT = std::max(length(gradT), 1.0);
    f.r = perp * (1 / f.rho);
    f.t = cross(a, f.r);
    auto extent = [&](const Vec3& u) {
        return std::max({std::abs(dot(dpdx, u)), std::abs(dot(dpdy, u)), diameter});
    };
    f.ft = extent(f.t), f.fr = extent(f.r), f.fz = extent(a);
    const double gt = dot(gradT, f.t), gr = dot(gradT, f.r);
    if (gr > 0.2 * f.gradT) f.scale = f.gradT / gr, f.shear = gt / gr;
    return true;
}

/// Seeded noise in the wood frame (tangential, radial, axial position in m) with cells of
/// `cell` metres, seen through the footprint's extents. The lattice never moves (a pattern
/// that scaled with the footprint would swim and show seams); an octave whose cells are
/// smaller than the footprint is scaled by one over the square root of the cells a footprint
/// averages, the standard deviation an area average of it has, and left out once that is
/// below 1/8. So fine texture keeps its strength in a bake of any resolution and fades to the
/// mean as the footprint grows; what is left of a sub-pixel octave is noise without a period,
/// which cannot make moire. Octave k has cells 2^-k as large and half the weight of the last.
double filteredNoise(uint64_t seed, const Vec3& position, const Vec3& cell, const WoodFrame& f,
                     int octaves) {
    double sum = 0, weight = 1;
    Vec3 c = cell;
    for (int k = 0; k < octaves; ++k) {
        const double averaged =
            std::max(1.0, f.ft / c.x) * std::max(1.0, f.fr / c.y) * std::max(1.0, f.fz / c.z);
        if (averaged > 64) break;  // finer octaves average out even more
        sum += weight / std::sqrt(averaged) *
               valueNoise(seed + 977 * k, position.x / c.x, position.y / c.y, position.z / c.z);
        weight *= 0.5;
        c = c * 0.5;
    }
    return sum;
}

/// Annuli about the axis, each with its own tangential lattice coordinate.
constexpr double kAnnulus = 0.01;  // m
constexpr double kAnnulusBlend = 0.15;

/// filteredNoise on a polar lattice: (arc, radius, axial position). The arc is measured at the
/// middle radius of a 1 cm annulus, so the lattice's sides are rays and circles (rho * theta
/// itself shears the lattice by theta: at an azimuth of 1.5 rad a step outwards moves the arc
/// 1.5 steps, and round cells became slanted streaks on end grain). Within 15 % of an annulus
/// edge the two annuli's noises are blended, variance kept, so nothing shows at the edge.
double polarNoise(uint64_t seed, const WoodFrame& f, const Vec3& cell, int octaves) {
    const double x = f.rho / kAnnulus, k = std::floor(x), t = x - k;
    auto at = [&](double annulus) {
        return filteredNoise(seed, {(annulus + 0.5) * kAnnulus * f.theta, f.rho, f.z}, cell, f,
                             octaves);
    };
    double w = 0, neighbour = k;
    if (t < kAnnulusBlend && k > 0)
        w = 0.5 * (1 - t / kAnnulusBlend), neighbour = k - 1;
    else if (t > 1 - kAnnulusBlend)
        w = 0.5 * (1 - (1 - t) / kAnnulusBlend), neighbour = k + 1;
    if (w == 0) return at(k);
    return ((1 - w) * at(k) + w * at(neighbour)) / std::sqrt((1 - w) * (1 - w) + w * w);
}

/// Fibre streaks: long along the fibre, narrow across it.
double fibreStreaks(const AnatomyParams& p, const WoodFrame& f) {
    if (p.fibreAmplitude <= 0) return 0;
    return p.fibreAmplitude * polarNoise(p.seed, f, {p.fibreWidth, p.fibreWidth, p.fibreLength}, 1);
}

/// Broad streaks of tone along the grain.
double toneStreaks(const AnatomyParams& p, const WoodFrame& f) {
    if (p.streakAmplitude <= 0) return 0;
    return p.streakAmplitude *
           polarNoise(p.seed + 57, f, {p.streakWidth, p.streakWidth, p.streakLength}, 2);
}

/// Each ring's own tone, seeded by its year; averaged away once a footprint spans rings.
double ringTone(const AnatomyParams& p, const WoodFrame& f) {
    if (p.ringTone <= 0) return 0;
    const double year = std::floor(f.T);
    if (!std::isfinite(year)) return 0;
    const double rings = f.gradT * std::max({f.ft, f.fr, f.fz});  // years under the footprint
    // The tone changes over the first fifth of the ring, from the last year's: rings differ
    // in tone, but the change has no edge of its own beside the late wood's.
    auto tone = [&](double y) {
        return 2 * cellRandom(p.seed, 71, static_cast<long long>(std::fmod(y, 1e15)), 0) - 1;
    };
    const double blend = smoothstep(0, 0.2, f.T - year);
    return p.ringTone / std::sqrt(1 + rings * rings) *
           (tone(year - 1) + (tone(year) - tone(year - 1)) * blend);
}

/// The cells themselves: a granular speckle at the scale of a few fibres, slightly drawn out
/// along them (what a photograph shows between the rings at 0.2 mm a pixel).
double speckle(const AnatomyParams& p, const WoodFrame& f) {
    if (p.speckleAmplitude <= 0) return 0;
    return p.speckleAmplitude *
           polarNoise(p.seed + 31, f,
                      {p.speckleSize, p.speckleRadial > 0 ? p.speckleRadial : p.speckleSize,
                       p.speckleLength},
                      2);
}

/// A ring-porous wood's late-wood vessels: their size against the band's and the share of
/// cells holding one (oak's and chestnut's small late-wood pores, in flames on end grain).
constexpr double kLateVesselSize = 0.4;
constexpr double kLateVesselShare = 0.3;

/// Vessels: their filtered coverage; `relief` gets the pit's slope.
double vessels(const AnatomyParams& p, const WoodFrame& f, double radial, double phase,
               Vec3& relief) {
    double pore = 0;
    if (p.pores != PoreKind::None) {
        const bool ringPorous = p.pores == PoreKind::RingPorous;
        const double half = std::min(0.5 * p.poreDiameter, 0.35 * p.poreSpacing);
        TubeCell c{p.poreSpacing, p.poreSpacing, p.poreLength, half, ringPorous ? 0.75 : 0.45};
        double rPos = radial;
        long long ring = 0;
        uint64_t salt = 101;
        if (ringPorous && phase < p.poreBand) {
            // Rows of vessels filling the early-wood band, cells aligned to the ring's start.
            const double band = p.poreBand / f.gradT;  // m
            const double rows = std::max(1.0, std::round(band / p.poreSpacing));
            c.rCell = band / rows;
            c.half = std::min(c.half, 0.4 * c.rCell);
            c.rows = (long long)rows;
            rPos = phase / f.gradT;
            ring = (long long)std::floor(f.T);
        } else if (ringPorous) {
            // Past the band the late wood's vessels: a few small ones, not an empty ring.
            c.half *= kLateVesselSize;
            c.probability = kLateVesselShare;
            salt = 111;
        } else if (phase > 0.75) {
            c.probability *= 0.5;  // fewer vessels in the late wood
        }
        const TubeSample t = tube(f, c, rPos, ring, p.seed, salt);
        pore = t.coverage;
        // The open pore is a pit: the relief falls towards its axis.
        relief = t.outward * (p.poreDepth * t.pit);
    }

    return pore;
}

/// Rays: sheets of constant azimuth; more of them further out (new rays start as the
/// circumference grows), so their spacing stays near raySpacing.
double rays(const AnatomyParams& p, const WoodFrame& f) {
    double ray = 0;
    if (p.rayWidth > 0 && p.raySpacing > 0) {
        const int base = std::max(8, (int)std::lround(kTwoPi * 0.05 / p.raySpacing));
        const double zCell = 2.5 * p.rayHeight;
        for (int k = 0; k < 3; ++k) {
            if (k > 0 && f.rho < 0.05 * (1 << (k - 1)) * 1.5) break;
            const long long n = (long long)base << k;
            const double u = (f.theta + std::numbers::pi) / kTwoPi * double(n);
            const long long j = ((long long)std::floor(u) % n + n) % n;
            if (k > 0 && cellRandom(p.seed, 200 + k, j, 0) < 0.5) continue;
            if (k == 0 && f.rho < rayStart(j, p.seed)) continue;
            const double centre = std::floor(u) + 0.2 + 0.6 * cellRandom(p.seed, 210 + k, j, 0);
            // A ray sheet is not a perfect plane through the pith: it wavers tangentially by a
            // few of its widths over millimetres, so a radial cut (quarter-sawn) passes in and
            // out of it and shows flecks, not all of a ray or none.
            const double waver = kRayWaver * p.rayWidth *
                                 valueNoise(p.seed + 290 + k, double(j), f.rho / kRayWaverRadial,
                                            f.z / kRayWaverAxial);
            const double dt = (u - centre) / double(n) * kTwoPi * f.rho + waver;  // m
            const double zc = f.z + zCell * cellRandom(p.seed, 220 + k, j, 0);
            const long long iz = (long long)std::floor(zc / zCell);
            const double h = p.rayHeight * (0.6 + 0.8 * cellRandom(p.seed, 230 + k, j, iz));
            const double z0 = (iz + (1 - h / zCell) * cellRandom(p.seed, 240 + k, j, iz)) * zCell;
            // Spindle-shaped in the tangential section (widest at mid-height), and of limited
            // radial extent: flecks, not bands, on quarter-sawn faces.
            const double along = (zc - z0) / h * 2 - 1;
            const double w = p.rayWidth * std::sqrt(std::max(0.0, 1 - along * along));
            const double rCell = 6 * p.rayHeight;
            const double rc = f.rho + rCell * cellRandom(p.seed, 250 + k, j, iz);
            const long long ir = (long long)std::floor(rc / rCell);
            const double r0 = (ir + 0.4 * cellRandom(p.seed, 260 + k, j, ir)) * rCell;
            const double cov = boxCoverage(dt, -0.5 * w, 0.5 * w, f.ft) *
                               boxCoverage(zc, z0, z0 + h, f.fz) *
                               boxCoverage(rc, r0, r0 + 0.6 * rCell, f.fr);
            const double spacing = kTwoPi * f.rho / double(n);
            // pi/4: the spindle's area against its box; 0.6: the radial share.
            const double mean = 0.785 * 0.6 * (p.rayWidth / spacing) * (p.rayHeight / zCell) *
                                (k ? 0.5 : raysStarted(f.rho));
            const double keep = std::min(detail(f.ft, spacing), detail(f.fz, zCell));
            ray = std::max(ray, keep * cov + (1 - keep) * mean);
        }
    }

    return ray;
}

/// Resin canals: sparse ducts in the late wood.
double resinCanals(const AnatomyParams& p, const WoodFrame& f, double radial, double phase) {
    double resin = 0;
    if (p.resinSpacing > 0 && phase > 0.55) {
        TubeCell c{p.resinSpacing, p.resinSpacing, 0.02,
                   std::min(0.5 * p.resinDiameter, 0.35 * p.resinSpacing), 0.3};
        resin = tube(f, c, radial, 0, p.seed, 301).coverage;
    }

    return resin;
}

}  // namespace

AnatomySample woodAnatomy(const AnatomyParams& p, const AnatomyAxis& axis, double T,
                          const Vec3& point, const Vec3& gradT, const Vec3& dpdx, const Vec3& dpdy,
                          double diameter, double weight) {
    AnatomySample out;
    if (!p.enabled || weight <= 0) return out;
    WoodFrame f;
    if (!woodFrameAt(axis, T, point, gradT, dpdx, dpdy, diameter, f)) return out;
    const double radial = f.T / f.gradT;  // radial position (m), rings at their true spacing
    const double phase = f.T - std::floor(f.T);
    const double fibre = fibreStreaks(p, f) + speckle(p, f) + toneStreaks(p, f) + ringTone(p, f);
    const double pore = vessels(p, f, radial, phase, out.reliefGradient);
    const double ray = rays(p, f);
    const double resin = resinCanals(p, f, radial, phase);
    const double b = (1 + weight * fibre) * (1 + weight * p.rayContrast * ray) *
                     (1 - weight * p.resinDarkening * resin);
    const double darkening = weight * p.poreDarkening * pore;
    out.brightness = b;
    out.pores = {1 - darkening * p.poreTint.r, 1 - darkening * p.poreTint.g,
                 1 - darkening * p.poreTint.b};
    out.reliefGradient = out.reliefGradient * weight;
    out.pore = pore * weight;
    out.ray = ray * weight;
    return out;
}

}  // namespace nenrin
