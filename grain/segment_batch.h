#pragma once
/// The segments kept for one tile, laid out as float arrays relative to the tile centre, so
/// "which of these is nearest to p" runs as a vectorised loop. Float only picks the nearest;
/// every distance that enters a growth time is recomputed in double.

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
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
    uint32_t id(uint32_t i) const { return ids_[i]; }
    std::span<const uint32_t> ids(uint32_t begin, uint32_t end) const {
        return std::span(ids_).subspan(begin, end - begin);
    }

    /// What one vectorised pass over a range found.
    struct Measured {
        float smallest;  ///< the smallest squared distance
        /// Above this, no squared distance can be the smallest in exact arithmetic: the
        /// smallest plus a bound on float rounding (relative to the origin, it grows with the
        /// distance D and the longest segment L as ~1e-6 (D^2 + 2 D L); taken 10x larger).
        float tieLimit;
    };
    /// Computes the squared distances from p to the segments [begin, end); then call nearest()
    /// on the same range.
    Measured measureFrom(const Vec3& p, uint32_t begin, uint32_t end);

    /// Index in [begin, end) of the segment nearest to the point last measured from. Float
    /// rounding depends on the batch's origin, so near-ties (below `measured.tieLimit`) are
    /// settled by `exact(index)` (the squared distance in double; equal distances go to the
    /// first index): the answer never depends on how points were batched.
    template <class ExactDistance2>
    uint32_t nearest(uint32_t begin, uint32_t end, const Measured& measured,
                     ExactDistance2&& exact) const {
        const float* d = distances_.data();
        // Usually one segment is clearly nearest and the float answer stands.
        const float limit = measured.tieLimit;
        uint32_t first = end, within = 0;
        for (uint32_t k = begin; k < end; ++k) {
            if (d[k] > limit) continue;
            if (within++ == 0) first = k;
        }
        if (within == 1) return first;
        uint32_t best = end;
        double bestDistance2 = 0;
        for (uint32_t k = first; k < end; ++k) {
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
