#include "renderer/stats/image_statistics.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>

#include "util/input_error.h"

namespace nenrin {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegrees = 180 / kPi;

double mean(const std::vector<double>& v) {
    return std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
}

/// np.std: the population standard deviation.
double populationStd(const std::vector<double>& v) {
    const double m = mean(v);
    double sum = 0;
    for (double x : v) sum += (x - m) * (x - m);
    return std::sqrt(sum / double(v.size()));
}

Plane difference(const Plane& a, const Plane& b) {
    Plane d(a.width, a.height);
    for (size_t i = 0; i < d.values.size(); ++i) d.values[i] = a.values[i] - b.values[i];
    return d;
}

Plane product(const Plane& a, const Plane& b) {
    Plane p(a.width, a.height);
    for (size_t i = 0; i < p.values.size(); ++i) p.values[i] = a.values[i] * b.values[i];
    return p;
}

/// Python's round(v, digits): the exact binary value rounded to `digits` decimals (half to
/// even), as fixed-point formatting does; v * 10^digits would round 1.2345 up, Python down.
double roundTo(double v, int digits) {
    return std::strtod(fmt::format("{:.{}f}", v, digits).c_str(), nullptr);
}

/// Circular spread (degrees) of the direction whose doubled angles are `angle2`: half the
/// circular standard deviation sqrt(-2 ln R) of the doubled angles.
double directionSpread(const Plane& angle2) {
    double c = 0, s = 0;
    for (double a : angle2.values) {
        c += std::cos(a);
        s += std::sin(a);
    }
    const double n = double(angle2.values.size());
    const double r = std::min(1.0, std::hypot(c / n, s / n));  // <= 1 but for rounding
    return std::sqrt(std::max(0.0, -2 * std::log(std::max(r, 1e-12)))) * kDegrees / 2;  // not -0
}

/// Median ratio of the eigenvalues of the fine layer's structure tensor (smoothed 16 px).
double fineAnisotropy(const Plane& fine) {
    const Plane fx = sobel(fine, 1), fy = sobel(fine, 0);
    const Plane kxx = gaussianFilter(product(fx, fx), 16),
                kyy = gaussianFilter(product(fy, fy), 16),
                kxy = gaussianFilter(product(fx, fy), 16);
    std::vector<double> ratios(kxx.values.size());
    for (size_t i = 0; i < ratios.size(); ++i) {
        const double xx = kxx.values[i], yy = kyy.values[i], xy = kxy.values[i];
        const double trace = xx + yy, spread = std::sqrt((xx - yy) * (xx - yy) + 4 * xy * xy);
        ratios[i] = (trace + spread) / std::max(trace - spread, 1e-9);
    }
    return median(std::move(ratios));
}

}  // namespace

GrainStructure grainStructure(const Plane& lightness) {
    const Plane smooth = gaussianFilter(lightness, 1.5);
    const Plane gx = sobel(smooth, 1), gy = sobel(smooth, 0);
    const Plane jxx = gaussianFilter(product(gx, gx), 8), jyy = gaussianFilter(product(gy, gy), 8),
                jxy = gaussianFilter(product(gx, gy), 8);
    GrainStructure s{Plane(lightness.width, lightness.height),
                     Plane(lightness.width, lightness.height)};
    for (size_t i = 0; i < s.angle2.values.size(); ++i) {
        const double xx = jxx.values[i], yy = jyy.values[i], xy = jxy.values[i];
        s.angle2.values[i] = std::atan2(2 * xy, xx - yy);
        s.coherence.values[i] = std::sqrt((xx - yy) * (xx - yy) + 4 * xy * xy) / (xx + yy + 1e-9);
    }
    return s;
}

ImageStatistics imageStatistics(const std::array<Plane, 3>& lab, Figures figures) {
    const Plane& lightness = lab[0];
    ImageStatistics s;
    for (size_t c = 0; c < 3; ++c) s.lab[c] = mean(lab[c].values);
    s.stdL = populationStd(lightness.values);
    const Plane blur4 = gaussianFilter(lightness, 4), blur16 = gaussianFilter(lightness, 16);
    const Plane fine = difference(lightness, blur4);
    s.fine = populationStd(fine.values);
    s.mid = populationStd(difference(blur4, blur16).values);
    if (figures == Figures::kAll) {
        s.dirSpread = directionSpread(grainStructure(lightness).angle2);
        s.fineAniso = fineAnisotropy(fine);
    }
    return s;
}

ImageStatistics roundedAsReported(const ImageStatistics& s) {
    ImageStatistics r;
    for (size_t c = 0; c < 3; ++c) r.lab[c] = roundTo(s.lab[c], 2);
    r.stdL = roundTo(s.stdL, 3);
    r.fine = roundTo(s.fine, 3);
    r.mid = roundTo(s.mid, 3);
    r.dirSpread = roundTo(s.dirSpread, 2);
    r.fineAniso = roundTo(std::min(s.fineAniso, 1e4), 2);
    return r;
}

StatisticsAgainst statisticsAgainst(const ImageStatistics& image, const ImageStatistics& photo,
                                    const std::string& photoPath) {
    if (!(photo.fine > 0 && photo.mid > 0 && photo.fineAniso > 0))
        throw InputError(photoPath, "",
                         fmt::format("fine {}, mid {}, fine_aniso {}: expected a photograph with "
                                     "texture to take ratios against",
                                     photo.fine, photo.mid, photo.fineAniso));
    StatisticsAgainst a;
    a.dE = roundTo(std::sqrt(std::pow(image.lab[0] - photo.lab[0], 2) +
                             std::pow(image.lab[1] - photo.lab[1], 2) +
                             std::pow(image.lab[2] - photo.lab[2], 2)),
                   2);
    a.fineRatio = roundTo(image.fine / photo.fine, 3);
    a.midRatio = roundTo(image.mid / photo.mid, 3);
    a.dirSpreadDiff = roundTo(image.dirSpread - photo.dirSpread, 2);
    a.fineAnisoRatio = roundTo(image.fineAniso / photo.fineAniso, 3);
    return a;
}

double weightedMedian(const std::vector<double>& values, const std::vector<double>& weights) {
    std::vector<size_t> order(values.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return values[a] < values[b]; });
    std::vector<double> cumulative(order.size());
    double sum = 0;
    for (size_t i = 0; i < order.size(); ++i) cumulative[i] = sum += weights[order[i]];
    const size_t at = size_t(std::lower_bound(cumulative.begin(), cumulative.end(), sum / 2) -
                             cumulative.begin());
    return values[order[std::min(at, order.size() - 1)]];
}

RingAgreement ringAgreement(const Plane& photoLightness, const Plane& growthTime,
                            const std::string& photoPath) {
    return ringAgreement(grainStructure(photoLightness), growthTime, photoPath);
}

RingAgreement ringAgreement(const GrainStructure& photo, const Plane& growthTime,
                            const std::string& photoPath) {
    const Plane t = gaussianFilter(growthTime, 2);
    const Plane ty = sobel(t, 0), tx = sobel(t, 1);
    constexpr int kBorder = 16;
    std::vector<double> angles, weights;
    for (int y = kBorder; y < t.height - kBorder; ++y)
        for (int x = kBorder; x < t.width - kBorder; ++x) {
            // The angle between two undirected lines, folded into [0, 90] degrees.
            const double d = photo.angle2.at(x, y) / 2 - std::atan2(ty.at(x, y), tx.at(x, y));
            const double folded = d + kPi / 2 - kPi * std::floor((d + kPi / 2) / kPi);
            angles.push_back(std::abs(folded - kPi / 2) * kDegrees);
            weights.push_back(photo.coherence.at(x, y));
        }
    double total = 0, within = 0;
    for (size_t i = 0; i < angles.size(); ++i) {
        total += weights[i];
        within += angles[i] < 15 ? weights[i] : 0;
    }
    if (!(total > 0))
        throw InputError(photoPath, "",
                         "no direction anywhere (a flat image): expected a photograph with rings");
    return {roundTo(weightedMedian(angles, weights), 2), roundTo(within / total, 3)};
}

}  // namespace nenrin
