#include "shader/ring_profile.h"

#include <cmath>

#include "grain/growth_terms.h"

namespace nenrin {

namespace {

constexpr int kTableSize = 1024;

/// The table cell of ring phase u (in cells, [0, kTableSize] for a finite T): never an index
/// outside the table, whatever T was (an infinite or NaN T has no phase: cell 0).
int tableCell(double& u) {
    if (!(u >= 0)) u = 0;
    int i = static_cast<int>(u);
    return i >= kTableSize ? kTableSize - 1 : i;
}

}  // namespace

RingProfile::RingProfile(const LateWoodShape& shape)
    : shape_(shape), values_(kTableSize + 1), cumulative_(kTableSize + 1) {
    for (int i = 0; i < kTableSize; ++i)
        values_[i] = lateWoodFraction(double(i) / kTableSize, shape);
    values_[kTableSize] = lateWoodFraction(1 - 1e-12, shape);  // the ring's end, from below
    // Simpson's rule on each table interval: E is smooth inside a ring, so the table's own
    // error (~1e-12) is far below anything visible; lookups interpolate linearly between
    // entries, exact for the integral up to O(1/N^2) of E's curvature.
    cumulative_[0] = 0;
    for (int i = 0; i < kTableSize; ++i) {
        double a = double(i) / kTableSize, b = double(i + 1) / kTableSize;
        double ea = lateWoodFraction(a, shape), eb = lateWoodFraction(b - 1e-15, shape);
        double em = lateWoodFraction(0.5 * (a + b), shape);
        cumulative_[i + 1] = cumulative_[i] + (b - a) * (ea + 4 * em + eb) / 6;
    }
}

double RingProfile::lateWood(double T) const {
    double u = (T - std::floor(T)) * kTableSize;
    int i = tableCell(u);
    return values_[i] + (u - i) * (values_[i + 1] - values_[i]);
}

double RingProfile::integral(double T) const {
    double rings = std::floor(T);
    double u = (T - rings) * kTableSize;
    int i = tableCell(u);
    double within = cumulative_[i] + (u - i) * (cumulative_[i + 1] - cumulative_[i]);
    return rings * cumulative_.back() + within;
}

double RingProfile::filtered(double T, double width) const {
    // Below a 1/200 of a ring the table's interpolation error would dominate: sample E.
    if (!(width > 5e-3)) return lateWood(T);
    return (integral(T + 0.5 * width) - integral(T - 0.5 * width)) / width;
}

double RingProfile::filteredSlope(double T, double width) const {
    if (!(width > 5e-3)) width = 5e-3;
    return (lateWood(T + 0.5 * width) - lateWood(T - 0.5 * width)) / width;
}

}  // namespace nenrin
