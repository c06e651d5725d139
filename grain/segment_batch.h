#pragma once
/// The segments kept for one tile, laid out as float arrays relative to the tile centre, so
/// "which of these is nearest to p" runs as a vectorised loop. Float only picks the nearest;
/// every distance that enters a growth time is recomputed in double.

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "util/vec3.h"

namespace nenrin {

class SegmentBatch {
public:
    void reset(const Vec3& origin) {
        origin_ = origin;
        for (auto* v : {&ax_, &ay_, &az_, &dx_, &dy_, &dz_, &inv_}) v->clear();
        ids_.clear();
    }
    void push(const Vec3& a, const Vec3& ab, double invLength2, uint32_t id) {
        Vec3 r = a - origin_;
        ax_.push_back(static_cast<float>(r.x));
        ay_.push_back(static_cast<float>(r.y));
        az_.push_back(static_cast<float>(r.z));
        dx_.push_back(static_cast<float>(ab.x));
        dy_.push_back(static_cast<float>(ab.y));
        dz_.push_back(static_cast<float>(ab.z));
        inv_.push_back(static_cast<float>(invLength2));
        ids_.push_back(id);
    }
    uint32_t size() const { return static_cast<uint32_t>(ids_.size()); }
    void truncate(uint32_t n) {
        for (auto* v : {&ax_, &ay_, &az_, &dx_, &dy_, &dz_, &inv_}) v->resize(n);
        ids_.resize(n);
    }
    uint32_t id(uint32_t i) const { return ids_[i]; }
    /// The squared distances of the last measureFrom(), one per segment.
    const float* distances() const { return distances_.data(); }

    /// Computes the squared distance from p to every segment of the batch, in one vectorised
    /// pass (cheaper than many short per-chain loops); then call nearest() per range.
    void measureFrom(const Vec3& p);

    /// Index in [begin, end) of the segment nearest to the point last measured from. Float
    /// rounding depends on the batch's origin, so near-ties are settled by `exact(index)`
    /// (the squared distance in double; equal distances go to the first index): the answer
    /// never depends on how points were batched.
    template <class ExactDistance2>
    uint32_t nearest(uint32_t begin, uint32_t end, ExactDistance2&& exact) const {
        const float* d = distances_.data();
        // One pass for the smallest and second smallest distance: usually they are far apart
        // and the float answer stands.
        uint32_t first = begin;
        float second = std::numeric_limits<float>::infinity();
        for (uint32_t k = begin + 1; k < end; ++k) {
            if (d[k] < d[first]) {
                second = d[first];
                first = k;
            } else {
                second = std::min(second, d[k]);
            }
        }
        const float limit = d[first] * (1 + 1e-4f) + 1e-8f;
        if (second > limit) return first;
        uint32_t best = end;
        double bestDistance2 = 0;
        for (uint32_t k = begin; k < end; ++k) {
            if (d[k] > limit) continue;
            double e = exact(k);
            if (best == end || e < bestDistance2) {  // in index order: ties keep the first
                best = k;
                bestDistance2 = e;
            }
        }
        return best;
    }

private:
    Vec3 origin_;
    std::vector<float> ax_, ay_, az_, dx_, dy_, dz_, inv_, distances_;
    std::vector<uint32_t> ids_;
};

}  // namespace nenrin
