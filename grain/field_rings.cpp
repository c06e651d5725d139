#include "grain/field_rings.h"

#include <algorithm>
#include <cmath>

#include "grain/ring_model.h"

namespace nenrin {

FieldRings fieldRingWidths(const Skeleton& skeleton, const GrainParams& params) {
    FieldRings rings{skeleton.ringWidths(), false};
    const RingModelParams& m = params.rings;
    rings.modelled = m.enabled && (rings.widths.empty() || m.replaceRecorded);
    if (!rings.modelled) return rings;
    // The grain's stochastic series, as long as the tree lived (or as the recorded one).
    double mean = m.meanWidth > 0 ? m.meanWidth : params.radialSpeed;
    int years = m.years > 0              ? m.years
                : params.fellingTime > 0 ? static_cast<int>(std::ceil(params.fellingTime)) + 1
                                         : 150;
    if (!rings.widths.empty()) {
        double sum = 0;
        for (double w : rings.widths) sum += w;
        if (m.meanWidth <= 0 && sum > 0) mean = sum / double(rings.widths.size());
        if (m.years <= 0) years = static_cast<int>(rings.widths.size());
    }
    rings.widths = generateRingWidths(m, years, mean);
    return rings;
}

double profileLateWoodShare(const LateWoodShape& shape) {
    double lo = 0, hi = 1;
    for (int i = 0; i < 50; ++i) {
        double mid = 0.5 * (lo + hi);
        (lateWoodFraction(mid, shape) < 0.5 ? lo : hi) = mid;
    }
    return 1 - 0.5 * (lo + hi);
}

LatewoodTiming fieldLatewoodTiming(const Skeleton& skeleton, const FieldRings& rings,
                                   const LateWoodShape& shape) {
    const std::vector<double>& widths = rings.widths;
    if (!skeleton.latewoodShares().empty())
        return LatewoodTiming(skeleton.latewoodShares(), profileLateWoodShare(shape));
    if (!rings.modelled || widths.empty()) return {};
    const double profileShare = profileLateWoodShare(shape);
    double mean = 0;
    for (double w : widths) mean += w / double(widths.size());
    std::vector<double> shares;
    for (double w : widths)
        shares.push_back(
            std::clamp(profileShare * std::sqrt(mean / std::max(w, 1e-9 * mean)), 0.05, 0.9));
    return LatewoodTiming(std::move(shares), profileShare);
}

}  // namespace nenrin
