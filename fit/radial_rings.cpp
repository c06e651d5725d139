#include "fit/radial_rings.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <tuple>
#include <utility>

#include "fit/ring_starts.h"
#include "grain/cielab.h"
#include "renderer/stats/stats_image.h"
#include "util/input_error.h"

namespace nenrin {

namespace {

/// Pixels this close to an image's edge are left out (resampling blurs them).
constexpr int kEdge = 2;
/// m: the shells the rings' period is measured on.
constexpr double kFineShell = 5e-5;
/// m: half the width of the band across the rings a ring series is measured along.
constexpr double kBandHalfWidth = 0.0015;

/// The faces' mean colour over shells `width` thick of the radius `radiusOf` from `inner` on;
/// shells no pixel fell in take their neighbours' colour, linearly.
template <class RadiusOf, class Keep>
std::vector<Rgb> shellColours(std::span<const FacePhoto> faces, RadiusOf&& radiusOf, Keep&& keep,
                              double inner, double outer, double width) {
    const size_t bins = std::max<size_t>(1, size_t(std::ceil((outer - inner) / width)));
    std::vector<Rgb> sum(bins);
    std::vector<double> count(bins, 0);
    for (const FacePhoto& f : faces)
        for (int y = kEdge; y < f.lightness.height - kEdge; ++y)
            for (int x = kEdge; x < f.lightness.width - kEdge; ++x) {
                if (!keep(f, x, y)) continue;
                const size_t b =
                    std::min(bins - 1, size_t((radiusOf(f.position(x, y)) - inner) / width));
                sum[b] =
                    sum[b] + Rgb{f.linear[0].at(x, y), f.linear[1].at(x, y), f.linear[2].at(x, y)};
                count[b] += 1;
            }
    std::vector<Rgb> columns(bins);
    long last = -1;
    for (size_t b = 0; b < bins; ++b) {
        if (count[b] == 0) continue;
        columns[b] = sum[b] * (1 / count[b]);
        for (long k = last + 1; k < long(b); ++k)
            columns[size_t(k)] =
                last < 0 ? columns[b]
                         : columns[size_t(last)] + (columns[b] - columns[size_t(last)]) *
                                                       (double(k - last) / double(long(b) - last));
        last = long(b);
    }
    for (size_t k = size_t(last + 1); k < bins; ++k) columns[k] = columns[size_t(last)];
    return columns;
}

/// The smallest and largest radius of the pixels `keep` picks ({inf, 0} for none).
template <class RadiusOf, class Keep>
std::pair<double, double> radiusRange(std::span<const FacePhoto> faces, RadiusOf&& radiusOf,
                                      Keep&& keep) {
    double inner = std::numeric_limits<double>::infinity(), outer = 0;
    for (const FacePhoto& f : faces)
        for (int y = kEdge; y < f.lightness.height - kEdge; ++y)
            for (int x = kEdge; x < f.lightness.width - kEdge; ++x)
                if (keep(f, x, y)) {
                    const double radius = radiusOf(f.position(x, y));
                    inner = std::min(inner, radius), outer = std::max(outer, radius);
                }
    return {inner, outer};
}

/// A moving average over `reach` samples to either side.
std::vector<double> boxMean(const std::vector<double>& v, long reach) {
    const long n = long(v.size());
    std::vector<double> out(v.size());
    for (long i = 0; i < n; ++i) {
        double s = 0;
        long m = 0;
        for (long j = std::max(0L, i - reach); j <= std::min(n - 1, i + reach); ++j)
            s += v[size_t(j)], ++m;
        out[size_t(i)] = s / double(m);
    }
    return out;
}

/// The rings' period along a strip of shells `width` thick: its lightness (smoothed over
/// 0.2 mm, less its trend over 10 mm) swings once up and once down per ring, so the period is
/// twice the strip's length over its swings (counted with hysteresis: a swing must cross from
/// below -0.5 to above 0.5 standard deviations, or back). Irregular ring widths do not confuse
/// it as they do an autocorrelation's peaks. 0 if the strip shows fewer than 3 rings or the
/// period comes out under `shortest`. `contrast`: the standard deviation of the detrended
/// lightness (L*), how clearly the rings stand out.
double ringPeriod(const std::vector<Rgb>& columns, double width, double shortest,
                  double& contrast) {
    const size_t n = columns.size();
    std::vector<double> L(n);
    for (size_t i = 0; i < n; ++i) L[i] = labFromLinearSrgb(columns[i]).L;
    const std::vector<double> smooth = boxMean(L, std::lround(1e-4 / width));
    const std::vector<double> trend = boxMean(smooth, std::lround(0.005 / width));
    double sd = 0;
    for (size_t i = 0; i < n; ++i) sd += (smooth[i] - trend[i]) * (smooth[i] - trend[i]);
    sd = std::sqrt(sd / double(std::max<size_t>(1, n)));
    contrast = sd;
    if (!(sd > 0)) return 0;
    int swings = 0, state = 0;
    size_t first = 0, last = 0;
    for (size_t i = 0; i < n; ++i) {
        const double z = (smooth[i] - trend[i]) / sd;
        const int side = z > 0.5 ? 1 : (z < -0.5 ? -1 : 0);
        if (side == 0 || side == state) continue;
        if (state != 0) {
            if (swings == 0) first = i;
            last = i, ++swings;
        }
        state = side;
    }
    if (swings < 6) return 0;
    const double period = 2 * double(last - first) * width / double(swings - 1);
    return period >= shortest ? period : 0.0;
}

/// A band of pixels across a face's rings: within `halfWidth` pixels of the line through the
/// face's centre along F's gradient there.
struct Band {
    double cx, cy, bx, by, halfWidth;
    bool operator()(const FacePhoto&, int x, int y) const {
        return std::abs((x - cx) * by - (y - cy) * bx) <= halfWidth;
    }
};

/// The band through the point `offset` (a share of the face's side) from its centre along
/// the rings there.
template <class RadiusOf>
Band bandAcross(const FacePhoto& f, RadiusOf&& radiusOf, double offset) {
    const double c = 0.5 * (f.lightness.width - 1);
    const int ic = f.lightness.width / 2, reach = 8;
    const double gx = radiusOf(f.position(ic + reach, ic)) - radiusOf(f.position(ic - reach, ic));
    const double gy = radiusOf(f.position(ic, ic + reach)) - radiusOf(f.position(ic, ic - reach));
    const double g = std::hypot(gx, gy);
    const double bx = g > 0 ? gx / g : 1.0, by = g > 0 ? gy / g : 0.0;
    const double pixel = length(f.face->right) / (f.lightness.width - 1);
    const double shift = offset * f.lightness.width;  // along the rings: (-by, bx)
    return {c - by * shift, c + bx * shift, bx, by, kBandHalfWidth / pixel};
}

/// The rings along the pixels `keep` picks: their period, shells a twentieth of it, the ring
/// starts at the sharpest edges; nothing if the strip shows no clear period or fewer than 3
/// whole rings. `base` gives the sample's radius range.
template <class RadiusOf, class Keep>
std::optional<RadialRings> ringsAlong(std::span<const FacePhoto> faces, RadiusOf&& radiusOf,
                                      Keep&& keep, const RadialRings& base,
                                      std::vector<double>& periods) {
    const auto [inner, outer] = radiusRange(faces, radiusOf, keep);
    if (!(outer > inner)) return std::nullopt;
    const double shortest = 5 * length(faces[0].face->right) / (kStatsSize - 1);
    double contrast = 0;
    const double period = ringPeriod(shellColours(faces, radiusOf, keep, inner, outer, kFineShell),
                                     kFineShell, shortest, contrast);
    if (period <= 0) return std::nullopt;
    periods.push_back(period);
    RadialRings r = base;
    r.contrast = contrast;
    r.binWidth = std::clamp(period / 20, 2e-5, 5e-4);
    const std::vector<Rgb> columns = shellColours(faces, radiusOf, keep, inner, outer, r.binWidth);
    std::vector<double> lightness;
    for (const Rgb& c : columns) lightness.push_back(labFromLinearSrgb(c).L);
    std::vector<int> starts = ringStarts(lightness, period / r.binWidth);
    if (starts.size() < 4) return std::nullopt;
    r.strip = colourStripFromBoundaries(columns, std::move(starts));
    r.boundaries.clear();
    for (int b : r.strip.boundaries) r.boundaries.push_back(inner + (b + 0.5) * r.binWidth);
    return r;
}

}  // namespace

RadialRings measureRadialRings(std::span<const FacePhoto> faces, const PithLine& pith,
                               const RingWarp& warp, const std::string& sampleFile,
                               double binWidth) {
    auto radiusOf = [&](const Vec3& p) { return warpedRingRadius(pith, warp, p); };
    auto everywhere = [](const FacePhoto&, int, int) { return true; };
    RadialRings best;
    std::tie(best.innerRadius, best.outerRadius) = radiusRange(faces, radiusOf, everywhere);
    // The strip over all faces is the longest; where F follows the rings only roughly it is
    // smeared, so the series may be measured as a dendrochronologist measures instead: along
    // a band across the rings, 3 mm wide, where F follows them closely (its direction off by
    // degrees moves a ring by more than its width over a whole face); bands through each
    // face's centre and a quarter of the face to either side. Of the strips whose rings stand
    // out nearly as clearly as the clearest's, the one whose rings span the longest radius.
    std::vector<RadialRings> candidates;
    std::vector<double> periods;
    if (auto all = ringsAlong(faces, radiusOf, everywhere, best, periods))
        candidates.push_back(*all);
    for (size_t k = 0; k < faces.size(); ++k)
        for (double offset : {0.0, -0.25, 0.25}) {
            const Band band = bandAcross(faces[k], radiusOf, offset);
            if (auto r = ringsAlong(faces.subspan(k, 1), radiusOf, band, best, periods)) {
                r->face = faces[k].face->name;
                candidates.push_back(*r);
            }
        }
    double clearest = 0;
    for (const RadialRings& c : candidates) clearest = std::max(clearest, c.contrast);
    bool found = false;
    double longest = 0;
    for (const RadialRings& c : candidates) {
        const double span = c.boundaries.back() - c.boundaries.front();
        if (c.contrast < 0.8 * clearest || (found && span <= longest)) continue;
        best = c, longest = span, found = true;
    }
    if (found) return best;
    if (periods.empty())
        throw InputError(sampleFile, "faces",
                         "no face shows rings across it: expected photographs of wood with "
                         "visible annual rings");
    // Rings are seen, but no strip shows 3 whole ones (a single flat-sawn face: wide arcs):
    // even rings of the median period, their colours from all faces.
    std::nth_element(periods.begin(), periods.begin() + long(periods.size() / 2), periods.end());
    const double period = periods[periods.size() / 2];
    best.binWidth = std::clamp(period / 20, 2e-5, 5e-4);
    const std::vector<Rgb> columns = shellColours(faces, radiusOf, everywhere, best.innerRadius,
                                                  best.outerRadius, best.binWidth);
    std::vector<int> starts;
    for (double r = 0; r < double(columns.size()); r += period / best.binWidth)
        starts.push_back(int(std::lround(r)));
    if (starts.size() < 2) starts = {0, int(columns.size()) - 1};
    best.strip = colourStripFromBoundaries(columns, starts);
    best.evenRings = true;
    best.boundaries.clear();
    for (int b : best.strip.boundaries)
        best.boundaries.push_back(best.innerRadius + (b + 0.5) * best.binWidth);
    return best;
}

std::vector<double> ringSeries(const std::vector<double>& boundaries, double outerRadius) {
    const double mean = (boundaries.back() - boundaries.front()) / double(boundaries.size() - 1);
    std::vector<double> widths;
    // (A warp can put the first boundary at or inside the line: no years before it then.)
    if (boundaries.front() > 0) {
        const int inner = std::max(1, int(std::lround(boundaries.front() / mean)));
        widths.assign(size_t(inner), boundaries.front() / inner);
    }
    for (size_t k = 1; k < boundaries.size(); ++k)
        widths.push_back(boundaries[k] - boundaries[k - 1]);
    for (double r = boundaries.back(); r < outerRadius + 3 * mean; r += mean)
        widths.push_back(mean);
    return widths;
}

}  // namespace nenrin
