#include "grain/ring_model.h"

#include <cmath>
#include <stdexcept>

#include "util/hash.h"
#include "util/random_draws.h"

namespace nenrin {

std::vector<double> generateRingWidths(const RingModelParams& p, int years, double meanWidth) {
    if (years <= 0 || !(meanWidth > 0))
        throw std::invalid_argument("generateRingWidths: expected years > 0 and a width > 0");
    // Independent streams: the stand's climate and this tree's own noise.
    SplitMix climate(mix64(p.climateSeed ^ 0x636c696d617465ull));
    SplitMix own(mix64(p.seed ^ 0x7472656573ull));
    const double phi = p.autocorrelation;
    const double sigma = std::sqrt(std::log1p(p.variation * p.variation));  // log-normal CV
    const double innovation = sigma * std::sqrt(1 - phi * phi);             // stationary sd = sigma
    const double common = std::sqrt(p.climateShare), individual = std::sqrt(1 - p.climateShare);

    std::vector<double> widths(static_cast<size_t>(years));
    double x = sigma * (common * drawNormal(climate) + individual * drawNormal(own));
    double trendSum = 0, noiseSum = 0;
    std::vector<double> trend(widths.size()), noise(widths.size());
    for (size_t t = 0; t < widths.size(); ++t) {
        if (t > 0)
            x = phi * x +
                innovation * (common * drawNormal(climate) + individual * drawNormal(own));
        trend[t] = 1 + (p.juvenileFactor - 1) * std::exp(-double(t) / p.juvenileYears);
        noise[t] = std::exp(x);
        trendSum += trend[t];
        noiseSum += trend[t] * noise[t];
    }
    // Scale so the mean width is exactly meanWidth (the log keeps its radius).
    const double scale = meanWidth * double(years) / noiseSum;
    for (size_t t = 0; t < widths.size(); ++t) widths[t] = scale * trend[t] * noise[t];
    return widths;
}

}  // namespace nenrin
