#include "fit/ring_starts.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace nenrin {

namespace {

std::vector<double> gaussianSmooth(const std::vector<double>& v, double sigma) {
    const int reach = std::max(1, int(std::ceil(3 * sigma)));
    std::vector<double> kernel;
    double total = 0;
    for (int d = -reach; d <= reach; ++d) {
        kernel.push_back(std::exp(-0.5 * d * d / (sigma * sigma)));
        total += kernel.back();
    }
    const int n = int(v.size());
    std::vector<double> out(v.size());
    for (int i = 0; i < n; ++i) {
        double s = 0;
        for (int d = -reach; d <= reach; ++d)
            s += kernel[size_t(d + reach)] * v[size_t(std::clamp(i + d, 0, n - 1))];
        out[size_t(i)] = s / total;
    }
    return out;
}

/// The value below which a share `q` of `v` lies.
double quantile(std::vector<double> v, double q) {
    if (v.empty()) return 0;
    const size_t k = std::min(v.size() - 1, size_t(q * double(v.size())));
    std::nth_element(v.begin(), v.begin() + long(k), v.end());
    return v[k];
}

/// The chain of `candidates` (sample indexes, increasing) with the most edge strength less a
/// cost per ring and for each gap's departure from `period` (samples); its score.
struct Chain {
    std::vector<int> starts;
    double score = -std::numeric_limits<double>::infinity();
};

Chain bestChain(const std::vector<int>& candidates, const std::vector<double>& strength,
                double period) {
    // Each ring's start brings its edge's strength (1 = the 95th percentile of the profile's
    // slopes, at most 1.5) less 0.4; a gap costs 2 ln^2(gap / period): a ring split in two at
    // a ring-porous hardwood's second row of pores costs 2 x 0.96, a ring left out (a gap of
    // two periods) 0.96. Gaps under a third of the period are not taken.
    constexpr double kPerRing = 0.4, kPerGap = 2;
    const size_t m = candidates.size();
    std::vector<double> best(m);
    std::vector<long> previous(m, -1);
    for (size_t j = 0; j < m; ++j) {
        best[j] = strength[j] - kPerRing;
        for (size_t i = 0; i < j; ++i) {
            const double gap = double(candidates[j] - candidates[i]) / period;
            if (gap < 1.0 / 3) continue;
            const double departure = std::log(gap);
            const double score = best[i] + strength[j] - kPerRing - kPerGap * departure * departure;
            if (score > best[j]) best[j] = score, previous[j] = long(i);
        }
    }
    Chain chain;
    if (m == 0) return chain;
    long k = long(std::max_element(best.begin(), best.end()) - best.begin());
    chain.score = best[size_t(k)];
    for (; k >= 0; k = previous[size_t(k)]) chain.starts.push_back(candidates[size_t(k)]);
    std::reverse(chain.starts.begin(), chain.starts.end());
    return chain;
}

}  // namespace

std::vector<int> ringStarts(const std::vector<double>& lightness, double samplesPerPeriod) {
    const int n = int(lightness.size());
    if (n < 3) return {};
    // A ring's sharp edge stays, its texture goes: smoothed over a fifteenth of the period.
    const std::vector<double> smooth = gaussianSmooth(lightness, samplesPerPeriod / 15);
    std::vector<double> slope(lightness.size(), 0.0);
    for (int i = 1; i + 1 < n; ++i)
        slope[size_t(i)] = 0.5 * (smooth[size_t(i + 1)] - smooth[size_t(i - 1)]);
    std::vector<double> rises, falls;
    for (double s : slope) (s > 0 ? rises : falls).push_back(std::abs(s));
    const double scale = std::max(quantile(rises, 0.95), quantile(falls, 0.95));
    if (!(scale > 0)) return {};
    // Rings start at rises (a conifer) or at falls (a ring-porous hardwood), and the period
    // given (counted from the profile's swings) may be a ring's texture's: chestnut's band of
    // pores is rows of dark dots with pale wood between, and the profile can swing twice a
    // ring (CN03's rings were counted 2.3 times over). So both signs and periods from 0.7 to
    // 3 times the one given are tried, and the chain scoring best is kept: more rings than
    // there are strong edges cost their weak edges, fewer cost the gaps they leave.
    Chain best;
    for (double sign : {1.0, -1.0}) {
        std::vector<int> candidates;
        std::vector<double> strength;
        for (int i = 1; i + 1 < n; ++i) {
            const double s = sign * slope[size_t(i)];
            if (s > 0.1 * scale && s >= sign * slope[size_t(i - 1)] &&
                s >= sign * slope[size_t(i + 1)]) {
                candidates.push_back(i);
                strength.push_back(std::min(1.5, s / scale));
            }
        }
        for (double factor = 0.7; factor < 3.05; factor *= 1.1) {
            Chain chain = bestChain(candidates, strength, factor * samplesPerPeriod);
            if (chain.score > best.score) best = std::move(chain);
        }
    }
    return best.starts;
}

}  // namespace nenrin
