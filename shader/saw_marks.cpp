#include "shader/saw_marks.h"

#include <algorithm>
#include <cmath>

#include "shader/finish.h"
#include "util/value_noise.h"

namespace nenrin {

namespace {

/// The sheets' normal and two directions along them: oblique to the tree's axes, so that the
/// faces of a block cut along them (end grain, flat- and quarter-sawn) all show diagonal marks.
const Vec3 kAcross = normalize(Vec3{1, 0.8, 1.2});
const Vec3 kAlong1 = normalize(cross(kAcross, Vec3{0, 0, 1}));
const Vec3 kAlong2 = cross(kAcross, kAlong1);

/// A mark runs on for about this many spacings before it changes depth.
constexpr double kMarkLength = 40;

double markNoise(uint64_t seed, double s, double u, double v) {
    return valueNoise(seed, s, u / kMarkLength, v / kMarkLength);
}

}  // namespace

SawMarkSample sawMarks(const Finish& finish, const Vec3& p, const Vec3& dpdx, const Vec3& dpdy,
                       double endGrain) {
    SawMarkSample out;
    if (finish.sawMarks <= 0 || finish.sawMarkSpacing <= 0) return out;
    const double spacing = finish.sawMarkSpacing;
    // Marks narrower than the footprint average out: scale by one over the square root of the
    // marks it spans, as the anatomy's noise, and leave them out past 64.
    const double across =
        std::max(std::abs(dot(dpdx, kAcross)), std::abs(dot(dpdy, kAcross))) / spacing;
    const double averaged = std::max(1.0, across);
    if (averaged > 64) return out;
    const double weight =
        finish.sawMarks * (0.2 + 0.8 * std::clamp(endGrain, 0.0, 1.0)) / std::sqrt(averaged);
    const double s = dot(p, kAcross) / spacing, u = dot(p, kAlong1) / spacing,
                 v = dot(p, kAlong2) / spacing;
    // Two octaves: the tooth pitch and its irregular half.
    const double n = markNoise(finish.sawMarkSeed, s, u, v) +
                     0.5 * markNoise(finish.sawMarkSeed + 1, 2 * s, u, v);
    out.brightness = weight * n;
    // The grooves' slope across the marks (a central difference over a tenth of a mark).
    const double h = 0.1;
    const double dn =
        (markNoise(finish.sawMarkSeed, s + h, u, v) - markNoise(finish.sawMarkSeed, s - h, u, v)) /
        (2 * h * spacing);
    out.reliefGradient = kAcross * (finish.sawMarkDepth * dn / std::sqrt(averaged));
    return out;
}

}  // namespace nenrin
