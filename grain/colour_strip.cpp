#include "grain/colour_strip.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "util/input_error.h"

namespace nenrin {

namespace {

std::vector<double> boxSmooth(const std::vector<double>& v, int radius) {
    std::vector<double> out(v.size());
    for (size_t i = 0; i < v.size(); ++i) {
        double sum = 0;
        int n = 0;
        for (int d = -radius; d <= radius; ++d) {
            long j = long(i) + d;
            if (j < 0 || j >= long(v.size())) continue;
            sum += v[size_t(j)], ++n;
        }
        out[i] = sum / n;
    }
    return out;
}

Lab meanLab(const std::vector<Lab>& v) {
    Lab m;
    for (const Lab& x : v) m.L += x.L, m.a += x.a, m.b += x.b;
    double n = double(std::max<size_t>(1, v.size()));
    return {m.L / n, m.a / n, m.b / n};
}

}  // namespace

ColourStrip analyseColourStrip(const std::vector<Rgb>& columns, const std::string& name) {
    if (columns.size() < 32)
        throw InputError(name, "",
                         fmt::format("{} columns: expected a strip at least 32 pixels "
                                     "long, pith to bark",
                                     columns.size()));
    std::vector<double> L;
    for (const Rgb& c : columns) L.push_back(labFromLinearSrgb(c).L);
    const std::vector<double> smooth = boxSmooth(L, 1);
    const std::vector<double> trend = boxSmooth(L, 20);
    // Late-wood lines: local minima of lightness clearly below the local level.
    std::vector<double> detrended(L.size());
    double spread = 0;
    for (size_t i = 0; i < L.size(); ++i) {
        detrended[i] = smooth[i] - trend[i];
        spread += detrended[i] * detrended[i];
    }
    spread = std::sqrt(spread / double(L.size()));
    // A line: the lowest point within 4 px, 1.3 sd of the detrended lightness (and at least
    // 0.5 L*) below the level around it. On data/colour-bars this finds 42 rings where the
    // strip's README counts about 41.
    const int window = 4;
    const double threshold = std::max(1.3 * spread, 0.5);
    std::vector<int> minima;
    for (int i = window; i + window < int(L.size()); ++i) {
        bool lowest = detrended[size_t(i)] < -threshold;
        for (int d = -window; d <= window && lowest; ++d)
            if (d != 0 && smooth[size_t(i + d)] < smooth[size_t(i)]) lowest = false;
        if (lowest && (minima.empty() || i - minima.back() > window)) minima.push_back(i);
    }
    // A ring starts where the late wood ends: the steepest rise after each line.
    std::vector<int> boundaries;
    for (size_t k = 0; k < minima.size(); ++k) {
        int from = minima[k];
        int to = k + 1 < minima.size() ? (minima[k] + minima[k + 1]) / 2
                                       : std::min<int>(int(L.size()) - 1, from + 2 * window);
        int best = from + 1;
        double rise = -1e9;
        for (int i = from; i < to && i + 1 < int(L.size()); ++i)
            if (smooth[size_t(i + 1)] - smooth[size_t(i)] > rise)
                rise = smooth[size_t(i + 1)] - smooth[size_t(i)], best = i + 1;
        boundaries.push_back(best);
    }
    if (boundaries.size() < 4)
        throw InputError(name, "",
                         fmt::format("found {} late-wood lines: expected a strip across at "
                                     "least 3 rings, pith on the left",
                                     boundaries.size()));
    return colourStripFromBoundaries(columns, std::move(boundaries));
}

ColourStrip colourStripFromBoundaries(const std::vector<Rgb>& columns,
                                      std::vector<int> boundaries) {
    std::vector<Lab> lab;
    std::vector<double> L;
    for (const Rgb& c : columns) {
        lab.push_back(labFromLinearSrgb(c));
        L.push_back(lab.back().L);
    }
    ColourStrip s;
    s.boundaries = std::move(boundaries);
    s.rings = int(s.boundaries.size()) - 1;
    const int bins = 33;
    s.lateWoodProfile.assign(bins, 0);
    std::vector<Lab> early, late;
    std::vector<Rgb> ringMeans;
    for (int k = 0; k < s.rings; ++k) {
        const int a = s.boundaries[size_t(k)], b = s.boundaries[size_t(k + 1)];
        s.ringWidths.push_back(double(b - a));
        std::vector<double> ringL(L.begin() + a, L.begin() + b);
        std::vector<double> sorted = ringL;
        std::sort(sorted.begin(), sorted.end());
        const double lateCut = sorted[size_t(std::max(0, int(sorted.size()) / 10 - 1))];
        const double earlyCut = sorted[size_t(sorted.size() * 2 / 3)];
        std::vector<Lab> e, l;
        Rgb mean;
        for (int i = a; i < b; ++i) {
            if (L[size_t(i)] >= earlyCut) e.push_back(lab[size_t(i)]);
            if (L[size_t(i)] <= lateCut) l.push_back(lab[size_t(i)]);
            mean = mean + columns[size_t(i)] * (1.0 / (b - a));
        }
        ringMeans.push_back(mean);
        Lab le = meanLab(e), ll = meanLab(l);
        early.push_back(le), late.push_back(ll);
        for (int j = 0; j < bins; ++j) {
            double x = a + (b - a - 1) * double(j) / (bins - 1);
            size_t i0 = size_t(std::floor(x));
            size_t i1 = std::min(i0 + 1, L.size() - 1);
            double v = L[i0] + (x - double(i0)) * (L[i1] - L[i0]);
            double E = le.L > ll.L ? std::clamp((le.L - v) / (le.L - ll.L), 0.0, 1.0) : 0.0;
            s.lateWoodProfile[size_t(j)] += E / s.rings;
        }
    }
    s.early = meanLab(early), s.late = meanLab(late);
    s.earlyWood = linearSrgbFromLab(s.early), s.lateWood = linearSrgbFromLab(s.late);
    s.widthStatistics = ringStatistics(s.ringWidths);
    // Heart and sapwood: the inner 40 % and the outer 30 % of the rings against all of them.
    auto meanOf = [&](int from, int to) {
        Rgb m;
        for (int k = from; k < to; ++k) m = m + ringMeans[size_t(k)] * (1.0 / (to - from));
        return m;
    };
    const Rgb all = meanOf(0, s.rings);
    const int inner = std::max(1, s.rings * 4 / 10), outer = std::max(1, s.rings * 3 / 10);
    s.heartwoodOffset = meanOf(0, inner) - all;
    s.sapwoodOffset = meanOf(s.rings - outer, s.rings) - all;
    s.heartwoodEnd = inner;
    return s;
}

}  // namespace nenrin
