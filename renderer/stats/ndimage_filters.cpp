#include "renderer/stats/ndimage_filters.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace nenrin {

namespace {

/// Correlates every line along `axis` (1: rows, 0: columns) with `weights` centred on the
/// middle tap, reading outside the line by reflection.
Plane correlate1d(const Plane& in, const std::vector<double>& weights, int axis) {
    Plane out(in.width, in.height);
    const int radius = int(weights.size() / 2);
    const int n = axis == 1 ? in.width : in.height, lines = axis == 1 ? in.height : in.width;
    // One line padded by reflection, so the inner loop reads without index arithmetic.
    std::vector<double> line(size_t(n) + 2 * size_t(radius));
    for (int l = 0; l < lines; ++l) {
        for (int i = -radius; i < n + radius; ++i) {
            const int j = reflectIndex(i, n);
            line[size_t(i + radius)] = axis == 1 ? in.at(j, l) : in.at(l, j);
        }
        for (int i = 0; i < n; ++i) {
            double sum = 0;
            for (size_t k = 0; k < weights.size(); ++k) sum += weights[k] * line[size_t(i) + k];
            (axis == 1 ? out.at(i, l) : out.at(l, i)) = sum;
        }
    }
    return out;
}

/// scipy's _gaussian_kernel1d: exp(-x^2 / 2 sigma^2) for |x| <= radius, divided by its sum.
std::vector<double> gaussianKernel(double sigma) {
    const int radius = int(4.0 * sigma + 0.5);
    std::vector<double> k(2 * size_t(radius) + 1);
    double sum = 0;
    for (int x = -radius; x <= radius; ++x)
        sum += k[size_t(x + radius)] = std::exp(-0.5 / (sigma * sigma) * double(x) * x);
    for (double& w : k) w /= sum;
    return k;
}

}  // namespace

int reflectIndex(int i, int n) {
    // Periodic with period 2n: a b c d d c b a | a b c d ...
    const int period = 2 * n;
    int j = i % period;
    if (j < 0) j += period;
    return j < n ? j : period - 1 - j;
}

Plane gaussianFilter(const Plane& plane, double sigma) {
    if (!(sigma > 0)) throw std::invalid_argument("gaussianFilter: sigma must be positive");
    const std::vector<double> k = gaussianKernel(sigma);
    // scipy filters axis 0 (columns) first, then axis 1 (rows).
    return correlate1d(correlate1d(plane, k, 0), k, 1);
}

Plane sobel(const Plane& plane, int axis) {
    if (axis != 0 && axis != 1) throw std::invalid_argument("sobel: axis must be 0 or 1");
    return correlate1d(correlate1d(plane, {-1, 0, 1}, axis), {1, 2, 1}, 1 - axis);
}

double median(std::vector<double> values) {
    if (values.empty()) throw std::invalid_argument("median of no values");
    const size_t mid = values.size() / 2;
    std::nth_element(values.begin(), values.begin() + mid, values.end());
    const double upper = values[mid];
    if (values.size() % 2 == 1) return upper;
    const double lower = *std::max_element(values.begin(), values.begin() + mid);
    return 0.5 * (lower + upper);
}

}  // namespace nenrin
