#include "grain/point_quarters.h"

#include <algorithm>

namespace nenrin {

void PointQuarters::reset(std::span<const Vec3> points, const Vec3& boxLo, const Vec3& boxHi) {
    points_ = points;
    boxLo_ = boxLo;
    boxHi_ = boxHi;
    split_ = false;
}

void PointQuarters::split() {
    if (split_) return;
    split_ = true;
    quarterOf_.resize(points_.size());
    boxes_.fill(PointBox{});
    // The box's sides, longest first.
    const double lower[3] = {boxLo_.x, boxLo_.y, boxLo_.z};
    const double upper[3] = {boxHi_.x, boxHi_.y, boxHi_.z};
    int axes[3] = {0, 1, 2};
    std::sort(axes, axes + 3,
              [&](int a, int b) { return upper[a] - lower[a] > upper[b] - lower[b]; });
    const int a = axes[0], b = axes[1];
    const double longest = upper[a] - lower[a], second = upper[b] - lower[b];
    // A squarish box in four by halving both sides; a long one in four along its length.
    const bool along = second < 0.5 * longest;
    const double midA = 0.5 * (lower[a] + upper[a]), midB = 0.5 * (lower[b] + upper[b]);
    const double quarterA = lower[a] + 0.25 * longest, threeQuartersA = lower[a] + 0.75 * longest;
    for (size_t i = 0; i < points_.size(); ++i) {
        const Vec3& p = points_[i];
        const double c[3] = {p.x, p.y, p.z};
        const int q = along ? (c[a] > quarterA) + (c[a] > midA) + (c[a] > threeQuartersA)
                            : 2 * (c[a] > midA) + (c[b] > midB);
        quarterOf_[i] = static_cast<uint8_t>(q);
        boxes_[q].add(p);
    }
}

}  // namespace nenrin
