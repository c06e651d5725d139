#include "grain/segment_batch.h"

#include <cmath>

#include "util/simd_clones.h"

namespace nenrin {

// Vectorised twice (util/simd_clones.h); the loops are elementwise (the minimum is kept per
// lane), so both versions give the same bits.
NENRIN_AVX2_CLONES SegmentBatch::Measured SegmentBatch::measureFrom(const Vec3& p, uint32_t begin,
                                                                    uint32_t end) {
    const float px = static_cast<float>(p.x - origin_.x);
    const float py = static_cast<float>(p.y - origin_.y);
    const float pz = static_cast<float>(p.z - origin_.z);
    if (distances_.size() < size()) distances_.resize(size());
    float* __restrict d = distances_.data();
    const float* __restrict ax = ax_.data();
    const float* __restrict ay = ay_.data();
    const float* __restrict az = az_.data();
    const float* __restrict dx = dx_.data();
    const float* __restrict dy = dy_.data();
    const float* __restrict dz = dz_.data();
    const float* __restrict inv = inv_.data();
    for (uint32_t k = begin; k < end; ++k) {  // branch-free: the compiler vectorises it
        float qx = px - ax[k], qy = py - ay[k], qz = pz - az[k];
        float t = (qx * dx[k] + qy * dy[k] + qz * dz[k]) * inv[k];
        t = std::max(0.f, std::min(1.f, t));
        float rx = qx - dx[k] * t, ry = qy - dy[k] * t, rz = qz - dz[k] * t;
        d[k] = rx * rx + ry * ry + rz * rz;
    }
    // The smallest distance and the longest segment (smallest 1 / L^2), kept per lane so that
    // the loop vectorises too.
    constexpr uint32_t kLanes = 8;
    float lanes[kLanes], shortest[kLanes];
    for (uint32_t l = 0; l < kLanes; ++l)
        lanes[l] = shortest[l] = std::numeric_limits<float>::infinity();
    uint32_t k = begin;
    for (; k + kLanes <= end; k += kLanes)
        for (uint32_t l = 0; l < kLanes; ++l) {
            lanes[l] = std::min(lanes[l], d[k + l]);
            shortest[l] = std::min(shortest[l], inv[k + l]);
        }
    float smallest = std::numeric_limits<float>::infinity();
    float inverseLongest = std::numeric_limits<float>::infinity();
    for (; k < end; ++k) {
        smallest = std::min(smallest, d[k]);
        inverseLongest = std::min(inverseLongest, inv[k]);
    }
    for (uint32_t l = 0; l < kLanes; ++l) {
        smallest = std::min(smallest, lanes[l]);
        inverseLongest = std::min(inverseLongest, shortest[l]);
    }
    const float longest = 1 / std::sqrt(inverseLongest);
    return {smallest, smallest * (1 + 1e-5f) + 2e-5f * std::sqrt(smallest) * longest + 1e-8f};
}

}  // namespace nenrin
