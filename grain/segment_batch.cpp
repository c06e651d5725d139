#include "grain/segment_batch.h"

namespace nenrin {

// Vectorised twice: AVX2 where the processor has it (8 floats per step), SSE2 otherwise;
// the loop is elementwise, so both give the same bits.
__attribute__((target_clones("avx2", "default"))) void SegmentBatch::measureFrom(const Vec3& p) {
    const float px = static_cast<float>(p.x - origin_.x);
    const float py = static_cast<float>(p.y - origin_.y);
    const float pz = static_cast<float>(p.z - origin_.z);
    const uint32_t n = size();
    distances_.resize(n);
    float* __restrict d = distances_.data();
    const float* __restrict ax = ax_.data();
    const float* __restrict ay = ay_.data();
    const float* __restrict az = az_.data();
    const float* __restrict dx = dx_.data();
    const float* __restrict dy = dy_.data();
    const float* __restrict dz = dz_.data();
    const float* __restrict inv = inv_.data();
    for (uint32_t k = 0; k < n; ++k) {  // branch-free: the compiler vectorises it
        float qx = px - ax[k], qy = py - ay[k], qz = pz - az[k];
        float t = (qx * dx[k] + qy * dy[k] + qz * dz[k]) * inv[k];
        t = std::max(0.f, std::min(1.f, t));
        float rx = qx - dx[k] * t, ry = qy - dy[k] * t, rz = qz - dz[k] * t;
        d[k] = rx * rx + ry * ry + rz * rz;
    }
}

}  // namespace nenrin
