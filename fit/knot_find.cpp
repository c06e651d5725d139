#include "fit/knot_find.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
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
/// The thresholds of a knot. On the Mokume faces the two knots (H11 C, F) measure evidence
/// 5.1 and 5.3, 6 eighths, 26 and 22 L* darker; the ten other faces' strongest centres at most
/// 3.2 (with up to 7 eighths and 7 L*): the evidence tells them apart.
constexpr double kMinEvidence = 4.5;
constexpr int kMinCoverage = 5;
constexpr double kMinDarkening = 5;  ///< L*
/// Or a dark patch the rings circle all round, whose own rings are faint (nenrin's own
/// knots: evidence 3.2-4.3, 8 eighths, 26 L* darker).
constexpr double kMinDarkPatchEvidence = 3;
constexpr int kMinDarkPatchCoverage = 7;
constexpr double kMinDarkPatchDarkening = 15;
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

/// The plane's values summed over rings 1 px wide round a centre (radius rounded), out to
/// `reach` px.
struct RingMeans {
    std::vector<double> sum, count;
    double mean(size_t r) const { return count[r] > 0 ? sum[r] / count[r] : 0; }
};
RingMeans ringMeans(const Plane& plane, const std::array<double, 2>& centre, int reach) {
    RingMeans rings{std::vector<double>(size_t(reach) + 1, 0.0),
                    std::vector<double>(size_t(reach) + 1, 0.0)};
    for (int y = 0; y < plane.height; ++y)
        for (int x = 0; x < plane.width; ++x) {
            const int r = int(std::lround(std::hypot(x - centre[0], y - centre[1])));
            if (r > reach) continue;
            rings.sum[size_t(r)] += plane.at(x, y);
            rings.count[size_t(r)] += 1;
        }
    return rings;
}

struct DarkWood {
    double radius = 0;  ///< pixels
    double edge = 0;    ///< the lightness of its edge
};

/// The radius (pixels) at which the mean lightness of rings around the centre first comes
/// halfway from the centre's up to the lightest ring's within reach: the edge of the dark knot
/// wood (the lightest ring, not the face's median: a knot darkens the wood around it too).
DarkWood darkWood(const Plane& blurred, const std::array<double, 2>& centre) {
    const RingMeans rings = ringMeans(blurred, centre, kVoteReach);
    double inner = 0, innerCount = 0, lightest = -1e300;
    for (size_t r = 0; r < rings.sum.size(); ++r) {
        if (rings.count[r] == 0) continue;
        if (r < kVoteNear) inner += rings.sum[r], innerCount += rings.count[r];
        lightest = std::max(lightest, rings.mean(r));
    }
    if (innerCount == 0) return {};
    const double half = 0.5 * (inner / innerCount + lightest);
    for (size_t r = 1; r < rings.sum.size(); ++r)
        if (rings.count[r] > 0 && rings.mean(r) >= half) return {double(r), half};
    return {kVoteReach, half};
}

/// The dark wood's outline in pixels: its long axis's angle (x right, y down) and the ratio
/// of its short to its long axis.
struct PixelEllipse {
    double angle = 0, roundness = 1;
};

/// The ellipse of the second moments of points weighted `w` at (px, py).
struct Moments {
    double w = 0, x = 0, y = 0, xx = 0, yy = 0, xy = 0;
    void add(double weight, double px, double py) {
        w += weight, x += weight * px, y += weight * py;
        xx += weight * px * px, yy += weight * py * py, xy += weight * px * py;
    }
    std::optional<PixelEllipse> ellipse() const {
        if (!(w > 0)) return std::nullopt;
        const double mx = x / w, my = y / w;
        const double cxx = xx / w - mx * mx, cyy = yy / w - my * my, cxy = xy / w - mx * my;
        const double mean = 0.5 * (cxx + cyy);
        const double spread = std::sqrt(0.25 * (cxx - cyy) * (cxx - cyy) + cxy * cxy);
        if (!(mean + spread > 0)) return std::nullopt;
        return PixelEllipse{0.5 * std::atan2(2 * cxy, cxx - cyy),
                            std::sqrt(std::max(0.0, mean - spread) / (mean + spread))};
    }
};

/// The ellipse of the dark wood within twice its radius (pixels darker than its edge,
/// weighted by how much darker): in the face's metres into `k`, and in pixels.
PixelEllipse darkOutline(FaceKnot& k, const Plane& blurred, const std::array<double, 2>& centre,
                         const DarkWood& dark, const SampleFace& face) {
    const double last = blurred.width - 1;
    const Vec3 right = face.right * (1 / last), down = face.up * (-1 / last);
    const double sx = length(right), sy = length(down), reach = 2 * dark.radius;
    Moments metres, pixels;
    for (int y = 0; y < blurred.height; ++y)
        for (int x = 0; x < blurred.width; ++x) {
            const double dx = x - centre[0], dy = y - centre[1];
            const double below = dark.edge - blurred.at(x, y);
            if (below <= 0 || std::hypot(dx, dy) > reach) continue;
            metres.add(below, dx * sx, dy * sy);
            pixels.add(below, dx, dy);
        }
    if (const std::optional<PixelEllipse> e = metres.ellipse()) {
        k.roundness = e->roundness;
        k.longAxis =
            normalize(right * (std::cos(e->angle) / sx) + down * (std::sin(e->angle) / sy));
    }
    return pixels.ellipse().value_or(PixelEllipse{});
}

/// Where a point of the image that `unstretched` makes came from: the long axis through
/// `centre` stretched back by 1 / roundness.
std::array<double, 2> stretchedBack(const std::array<double, 2>& p,
                                    const std::array<double, 2>& centre, const PixelEllipse& e) {
    const double c = std::cos(e.angle), s = std::sin(e.angle);
    const double dx = p[0] - centre[0], dy = p[1] - centre[1];
    const double along = (dx * c + dy * s) / e.roundness, across = -dx * s + dy * c;
    return {centre[0] + along * c - across * s, centre[1] + along * s + across * c};
}

/// The image squeezed along the outline's long axis through `centre` by its roundness, so that
/// an oblique branch's oval rings become circles (bilinear, the edge repeated outside).
Plane unstretched(const Plane& image, const std::array<double, 2>& centre, const PixelEllipse& e) {
    Plane out(image.width, image.height);
    auto at = [&](int x, int y) {
        return image.at(std::clamp(x, 0, image.width - 1), std::clamp(y, 0, image.height - 1));
    };
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            const std::array<double, 2> p = stretchedBack({double(x), double(y)}, centre, e);
            const double fx = std::floor(p[0]), fy = std::floor(p[1]);
            const double tx = p[0] - fx, ty = p[1] - fy;
            const int ix = int(fx), iy = int(fy);
            out.at(x, y) = (1 - ty) * ((1 - tx) * at(ix, iy) + tx * at(ix + 1, iy)) +
                           ty * ((1 - tx) * at(ix, iy + 1) + tx * at(ix + 1, iy + 1));
        }
    return out;
}

/// The mean spacing (pixels) of the dark rings round the centre within `reach`: minima of
/// the mean lightness of 1 px rings, less its 9 px running mean, at least 3 px apart and
/// 0.3 L* deep; 0 with fewer than 3.
double ringSpacing(const Plane& lightness, const std::array<double, 2>& centre, int reach) {
    const RingMeans rings = ringMeans(lightness, centre, reach);
    std::vector<double> profile(rings.sum.size(), 0.0), detrended(rings.sum.size(), 0.0);
    for (size_t r = 0; r < profile.size(); ++r) profile[r] = rings.mean(r);
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

namespace {

struct RingCentre {
    std::array<double, 2> centre;  ///< pixels
    double evidence = 0;
    int coverage = 0;
};

/// The place the most ring normals point at (votes, least squares, the innermost loop), or
/// none (no ring structure, or a centre off the image).
std::optional<RingCentre> ringCentre(const Plane& lightness) {
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
    const double lastX = votes.width - 1, lastY = votes.height - 1;
    if (!(centre[0] >= 0 && centre[0] <= lastX && centre[1] >= 0 && centre[1] <= lastY))
        return std::nullopt;  // a centre off the face: nothing to place a knot by
    centre = focusCentre(o, centre);
    return RingCentre{centre, *peak / mean, coverage(o, centre)};
}

/// The knot's figures at a ring centre; its outline in pixels into `outline`.
FaceKnot measureKnot(const Plane& lightness, const Plane& blurred, const SampleFace& face,
                     const RingCentre& found, PixelEllipse& outline) {
    const double last = lightness.width - 1;
    const std::array<double, 2>& centre = found.centre;
    FaceKnot k;
    k.face = face.name;
    k.column = centre[0], k.row = centre[1];
    k.centre = face.at(centre[0] / last, centre[1] / last);
    k.evidence = found.evidence;
    k.coverage = found.coverage;
    k.darkening = median(lightness.values) -
                  blurred.at(int(std::lround(centre[0])), int(std::lround(centre[1])));
    const double pixel = 0.5 * (length(face.right) + length(face.up)) / last;
    const DarkWood dark = darkWood(blurred, centre);
    k.radius = dark.radius * pixel;
    k.longAxis = normalize(face.right);
    outline = darkOutline(k, blurred, centre, dark, face);
    k.ringSpacing = ringSpacing(lightness, centre, int(std::min(dark.radius, 30.0))) * pixel;
    return k;
}

/// Outlines rounder than this are taken as circles.
constexpr double kRoundEnough = 0.85;

}  // namespace

std::optional<FaceKnot> strongestRingCentre(const Plane& lightness, const SampleFace& face) {
    const std::optional<RingCentre> found = ringCentre(lightness);
    if (!found) return std::nullopt;
    const Plane blurred = gaussianFilter(lightness, 5);
    PixelEllipse outline;
    FaceKnot k = measureKnot(lightness, blurred, face, *found, outline);
    if (outline.roundness >= kRoundEnough) return k;
    // An oval: its normals do not meet at its centre. Found again with the oval squeezed
    // round, and kept if its rings point at one place more clearly so.
    const Plane round = unstretched(lightness, found->centre, outline);
    const std::optional<RingCentre> again = ringCentre(round);
    if (!again || again->evidence <= found->evidence) return k;
    RingCentre back = *again;
    back.centre = stretchedBack(again->centre, found->centre, outline);
    const double last = lightness.width - 1;
    if (!(back.centre[0] >= 0 && back.centre[0] <= last && back.centre[1] >= 0 &&
          back.centre[1] <= last))
        return k;
    PixelEllipse unused;
    FaceKnot oval = measureKnot(lightness, blurred, face, back, unused);
    // Its rings' spacing across the branch: along the squeezed image's radius.
    const double pixel = 0.5 * (length(face.right) + length(face.up)) / last;
    oval.ringSpacing =
        ringSpacing(round, again->centre, int(std::min(oval.radius / pixel, 30.0))) * pixel;
    return oval;
}

bool looksLikeKnot(const FaceKnot& k, const PithLine* pith) {
    const bool ringed =
        k.evidence >= kMinEvidence && k.coverage >= kMinCoverage && k.darkening >= kMinDarkening;
    const bool darkPatch = k.evidence >= kMinDarkPatchEvidence &&
                           k.coverage >= kMinDarkPatchCoverage &&
                           k.darkening >= kMinDarkPatchDarkening;
    return (ringed || darkPatch) && !(pith && ringRadius(*pith, k.centre) < kPithClearance);
}

std::optional<FaceKnot> findFaceKnot(const Plane& lightness, const SampleFace& face,
                                     const PithLine* pith) {
    std::optional<FaceKnot> k = strongestRingCentre(lightness, face);
    if (k && !looksLikeKnot(*k, pith)) k.reset();
    return k;
}

}  // namespace nenrin
