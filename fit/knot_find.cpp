#include "fit/knot_find.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace nenrin {

namespace {

/// Votes reach this far along a ring normal (pixels of 256: a third of the face).
constexpr int kVoteReach = 80;
/// Nearer than this the ring direction is too curved to vote.
constexpr int kVoteNear = 3;
/// The refining discs' radii (pixels), then how far a normal line may pass from the centre
/// and still count (pixels, a Gaussian's sigma).
constexpr std::array<double, 4> kRefineDiscs = {60, 30, 20, 12};
constexpr double kLineSigma = 3;
/// Last, the centre is moved (up to kFocusReach px) to where the largest share of the ring
/// normals within kFocusDisc px point at it within kFocusSigma: the innermost loop. The
/// least squares settle between the eccentric ovals of an oblique branch (3 mm off on H11 F).
constexpr int kFocusReach = 25;
constexpr double kFocusDisc = 14, kFocusSigma = 1.5;
/// The thresholds of a knot (measured on the Mokume faces: knots 5.5-5.9 and 5-6 eighths,
/// plain faces at most 3.7 and the trunk's rings 2-4 eighths).
constexpr double kMinEvidence = 4.5;
constexpr int kMinCoverage = 5;
constexpr double kMinDarkening = 5;  ///< L*
constexpr double kPithClearance = 0.010;

struct Orientation {
    Plane angle;     ///< the ring normal's angle, x right and y down
    Plane strength;  ///< coherence times the gradient's magnitude, mean 1
};

/// The structure tensor at the scale of a knot's rings (a few pixels apart): gradients of
/// the lightness blurred by 1 px, averaged over 3 px.
Orientation ringOrientation(const Plane& lightness) {
    const Plane smooth = gaussianFilter(lightness, 1);
    const Plane gx = sobel(smooth, 1), gy = sobel(smooth, 0);
    Plane xx = gx, yy = gy, xy = gx;
    for (size_t i = 0; i < xx.values.size(); ++i) {
        xx.values[i] = gx.values[i] * gx.values[i];
        yy.values[i] = gy.values[i] * gy.values[i];
        xy.values[i] = gx.values[i] * gy.values[i];
    }
    xx = gaussianFilter(xx, 3), yy = gaussianFilter(yy, 3), xy = gaussianFilter(xy, 3);
    Orientation o{Plane(lightness.width, lightness.height),
                  Plane(lightness.width, lightness.height)};
    double sum = 0;
    for (size_t i = 0; i < xx.values.size(); ++i) {
        const double a = xx.values[i], b = yy.values[i], c = xy.values[i];
        const double trace = a + b, spread = std::sqrt((a - b) * (a - b) + 4 * c * c);
        o.angle.values[i] = 0.5 * std::atan2(2 * c, a - b);
        o.strength.values[i] = trace > 1e-12 ? spread / std::sqrt(trace) : 0;
        sum += o.strength.values[i];
    }
    if (sum > 0)
        for (double& v : o.strength.values) v *= double(o.strength.values.size()) / sum;
    return o;
}

/// Every other pixel votes along its ring normal, 1/distance (a circle of rings then votes
/// the same at every radius).
Plane centreVotes(const Orientation& o) {
    const int w = o.angle.width, h = o.angle.height;
    Plane votes(w, h);
    for (int y = 0; y < h; y += 2)
        for (int x = 0; x < w; x += 2) {
            const double a = o.angle.at(x, y), weight = o.strength.at(x, y);
            const double c = std::cos(a), s = std::sin(a);
            for (int t = kVoteNear; t <= kVoteReach; ++t)
                for (int sign : {-1, 1}) {
                    const int px = int(std::lround(x + sign * t * c));
                    const int py = int(std::lround(y + sign * t * s));
                    if (px >= 0 && px < w && py >= 0 && py < h) votes.at(px, py) += weight / t;
                }
        }
    return gaussianFilter(votes, 2);
}

/// The point nearest (least squares) to the normal lines of the pixels within `disc` of
/// `centre` that pass near it.
std::array<double, 2> refineCentre(const Orientation& o, std::array<double, 2> centre,
                                   double disc) {
    double a11 = 0, a12 = 0, a22 = 0, b1 = 0, b2 = 0;
    for (int y = 0; y < o.angle.height; ++y)
        for (int x = 0; x < o.angle.width; ++x) {
            const double dx = x - centre[0], dy = y - centre[1], r = std::hypot(dx, dy);
            if (r <= kVoteNear || r >= disc) continue;
            const double a = o.angle.at(x, y), tx = -std::sin(a), ty = std::cos(a);
            const double miss = tx * dx + ty * dy;  // the normal line's distance from centre
            const double w =
                o.strength.at(x, y) * std::exp(-miss * miss / (2 * kLineSigma * kLineSigma));
            const double along = tx * x + ty * y;
            a11 += w * tx * tx, a12 += w * tx * ty, a22 += w * ty * ty;
            b1 += w * tx * along, b2 += w * ty * along;
        }
    const double det = a11 * a22 - a12 * a12;
    if (!(det > 1e-9 * (a11 + a22) * (a11 + a22))) return centre;
    return {(b1 * a22 - b2 * a12) / det, (a11 * b2 - a12 * b1) / det};
}

/// The share of the ring normals within kFocusDisc of (cx, cy) whose lines pass within about
/// kFocusSigma of it.
double pointingShare(const Orientation& o, double cx, double cy) {
    const int r = int(kFocusDisc);
    double pointing = 0, total = 0;
    for (int y = std::max(0, int(cy) - r); y <= std::min(o.angle.height - 1, int(cy) + r + 1); ++y)
        for (int x = std::max(0, int(cx) - r); x <= std::min(o.angle.width - 1, int(cx) + r + 1);
             ++x) {
            const double dx = x - cx, dy = y - cy, d = std::hypot(dx, dy);
            if (d <= 2 || d >= kFocusDisc) continue;
            const double a = o.angle.at(x, y);
            const double miss = -std::sin(a) * dx + std::cos(a) * dy;
            const double w = o.strength.at(x, y);
            pointing += w * std::exp(-miss * miss / (2 * kFocusSigma * kFocusSigma));
            total += w;
        }
    return total > 0 ? pointing / total : 0;
}

std::array<double, 2> focusCentre(const Orientation& o, const std::array<double, 2>& centre) {
    std::array<double, 2> best = centre;
    double bestShare = -1;
    for (int dy = -kFocusReach; dy <= kFocusReach; ++dy)
        for (int dx = -kFocusReach; dx <= kFocusReach; ++dx) {
            const double cx = std::round(centre[0]) + dx, cy = std::round(centre[1]) + dy;
            if (cx < 0 || cy < 0 || cx > o.angle.width - 1 || cy > o.angle.height - 1) continue;
            const double share = pointingShare(o, cx, cy);
            if (share > bestShare) bestShare = share, best = {cx, cy};
        }
    return best;
}

/// Eighths of a turn around the centre holding at least 5 % of the ring normals that point
/// at it (within the first refining disc).
int coverage(const Orientation& o, const std::array<double, 2>& centre) {
    std::array<double, 8> share{};
    double total = 0;
    for (int y = 0; y < o.angle.height; ++y)
        for (int x = 0; x < o.angle.width; ++x) {
            const double dx = x - centre[0], dy = y - centre[1], r = std::hypot(dx, dy);
            if (r <= kVoteNear || r >= kRefineDiscs[0]) continue;
            const double a = o.angle.at(x, y);
            const double miss = -std::sin(a) * dx + std::cos(a) * dy;
            const double w =
                o.strength.at(x, y) * std::exp(-miss * miss / (2 * kLineSigma * kLineSigma));
            const int bin = std::clamp(int((std::atan2(dy, dx) + M_PI) / (2 * M_PI) * 8), 0, 7);
            share[size_t(bin)] += w;
            total += w;
        }
    return total > 0 ? int(std::count_if(share.begin(), share.end(),
                                         [&](double s) { return s > 0.05 * total; }))
                     : 0;
}

struct DarkWood {
    double radius = 0;  ///< pixels
    double edge = 0;    ///< the lightness of its edge
};

/// The radius (pixels) at which the mean lightness of rings around the centre first comes
/// halfway from the centre's up to the lightest ring's within reach: the edge of the dark knot
/// wood (the lightest ring, not the face's median: a knot darkens the wood around it too).
DarkWood darkWood(const Plane& blurred, const std::array<double, 2>& centre) {
    std::array<double, kVoteReach + 1> sum{}, count{};
    for (int y = 0; y < blurred.height; ++y)
        for (int x = 0; x < blurred.width; ++x) {
            const int r = int(std::lround(std::hypot(x - centre[0], y - centre[1])));
            if (r > kVoteReach) continue;
            sum[size_t(r)] += blurred.at(x, y);
            count[size_t(r)] += 1;
        }
    double inner = 0, innerCount = 0, lightest = -1e300;
    for (size_t r = 0; r < sum.size(); ++r) {
        if (count[r] == 0) continue;
        if (r < kVoteNear) inner += sum[r], innerCount += count[r];
        lightest = std::max(lightest, sum[r] / count[r]);
    }
    if (innerCount == 0) return {};
    const double half = 0.5 * (inner / innerCount + lightest);
    for (size_t r = 1; r < sum.size(); ++r)
        if (count[r] > 0 && sum[r] / count[r] >= half) return {double(r), half};
    return {kVoteReach, half};
}

/// The ellipse of the dark wood within twice its radius (pixels darker than its edge,
/// weighted by how much darker), in the face's metres.
void darkOutline(FaceKnot& k, const Plane& blurred, const std::array<double, 2>& centre,
                 const DarkWood& dark, const SampleFace& face) {
    const double last = blurred.width - 1;
    const Vec3 right = face.right * (1 / last), down = face.up * (-1 / last);
    const double sx = length(right), sy = length(down), reach = 2 * dark.radius;
    double w = 0, mx = 0, my = 0, xx = 0, yy = 0, xy = 0;
    for (int y = 0; y < blurred.height; ++y)
        for (int x = 0; x < blurred.width; ++x) {
            const double dx = x - centre[0], dy = y - centre[1];
            const double below = dark.edge - blurred.at(x, y);
            if (below <= 0 || std::hypot(dx, dy) > reach) continue;
            const double px = dx * sx, py = dy * sy;
            w += below, mx += below * px, my += below * py;
            xx += below * px * px, yy += below * py * py, xy += below * px * py;
        }
    if (!(w > 0)) return;
    mx /= w, my /= w;
    xx = xx / w - mx * mx, yy = yy / w - my * my, xy = xy / w - mx * my;
    const double mean = 0.5 * (xx + yy), spread = std::sqrt(0.25 * (xx - yy) * (xx - yy) + xy * xy);
    if (!(mean + spread > 0)) return;
    k.roundness = std::sqrt(std::max(0.0, mean - spread) / (mean + spread));
    const double angle = 0.5 * std::atan2(2 * xy, xx - yy);
    k.longAxis = normalize(right * (std::cos(angle) / sx) + down * (std::sin(angle) / sy));
}

/// The mean spacing (pixels) of the dark rings round the centre within `reach`: minima of
/// the mean lightness of 1 px rings, less its 9 px running mean, at least 3 px apart and
/// 0.3 L* deep; 0 with fewer than 3.
double ringSpacing(const Plane& lightness, const std::array<double, 2>& centre, int reach) {
    std::vector<double> sum(size_t(reach) + 1, 0.0), count(size_t(reach) + 1, 0.0);
    for (int y = 0; y < lightness.height; ++y)
        for (int x = 0; x < lightness.width; ++x) {
            const int r = int(std::lround(std::hypot(x - centre[0], y - centre[1])));
            if (r > reach) continue;
            sum[size_t(r)] += lightness.at(x, y);
            count[size_t(r)] += 1;
        }
    std::vector<double> profile(sum.size(), 0.0), detrended(sum.size(), 0.0);
    for (size_t r = 0; r < sum.size(); ++r) profile[r] = count[r] > 0 ? sum[r] / count[r] : 0;
    for (int r = 0; r <= reach; ++r) {
        double s = 0, n = 0;
        for (int q = std::max(0, r - 4); q <= std::min(reach, r + 4); ++q)
            s += profile[size_t(q)], ++n;
        detrended[size_t(r)] = profile[size_t(r)] - s / n;
    }
    std::vector<int> minima;
    for (int r = kVoteNear; r < reach; ++r) {
        const double v = detrended[size_t(r)];
        if (v < -0.3 && v < detrended[size_t(r - 1)] && v <= detrended[size_t(r + 1)] &&
            (minima.empty() || r - minima.back() >= 3))
            minima.push_back(r);
    }
    return minima.size() >= 3 ? double(minima.back() - minima.front()) / double(minima.size() - 1)
                              : 0.0;
}

}  // namespace

std::optional<FaceKnot> strongestRingCentre(const Plane& lightness, const SampleFace& face) {
    const Orientation o = ringOrientation(lightness);
    const Plane votes = centreVotes(o);
    const auto peak = std::max_element(votes.values.begin(), votes.values.end());
    double mean = 0;
    for (double v : votes.values) mean += v;
    mean /= double(votes.values.size());
    if (!(mean > 0)) return std::nullopt;
    const size_t index = size_t(peak - votes.values.begin());
    std::array<double, 2> centre = {double(index % size_t(votes.width)),
                                    double(index / size_t(votes.width))};
    for (double disc : kRefineDiscs) centre = refineCentre(o, centre, disc);
    if (centre[0] >= 0 && centre[1] >= 0 && centre[0] <= votes.width - 1 &&
        centre[1] <= votes.height - 1)
        centre = focusCentre(o, centre);
    const double last = lightness.width - 1;
    if (!(centre[0] >= 0 && centre[0] <= last && centre[1] >= 0 && centre[1] <= last))
        return std::nullopt;  // a centre off the face: nothing to place a knot by
    FaceKnot k;
    k.face = face.name;
    k.column = centre[0], k.row = centre[1];
    k.centre = face.at(centre[0] / last, centre[1] / last);
    k.evidence = *peak / mean;
    k.coverage = coverage(o, centre);
    const Plane blurred = gaussianFilter(lightness, 5);
    const double faceMedian = median(lightness.values);
    k.darkening = faceMedian - blurred.at(int(std::lround(centre[0])), int(std::lround(centre[1])));
    const double pixel = 0.5 * (length(face.right) + length(face.up)) / last;
    const DarkWood dark = darkWood(blurred, centre);
    k.radius = dark.radius * pixel;
    k.longAxis = normalize(face.right);
    darkOutline(k, blurred, centre, dark, face);
    k.ringSpacing = ringSpacing(lightness, centre, int(std::min(dark.radius, 30.0))) * pixel;
    return k;
}

bool looksLikeKnot(const FaceKnot& k, const PithLine* pith) {
    return k.evidence >= kMinEvidence && k.coverage >= kMinCoverage &&
           k.darkening >= kMinDarkening && !(pith && ringRadius(*pith, k.centre) < kPithClearance);
}

std::optional<FaceKnot> findFaceKnot(const Plane& lightness, const SampleFace& face,
                                     const PithLine* pith) {
    std::optional<FaceKnot> k = strongestRingCentre(lightness, face);
    if (k && !looksLikeKnot(*k, pith)) k.reset();
    return k;
}

}  // namespace nenrin
