#pragma once
/// The result of a bake: a 2D or 3D grid of samples with the channels every nenrin output
/// carries: R, G, B (scene-linear albedo), A (coverage: 0 outside the felled log), T (growth time,
/// years), knot (0..1).

#include <array>
#include <map>
#include <string>
#include <vector>

#include "util/vec3.h"

namespace nenrin {

inline constexpr std::array<const char*, 6> kBakeChannels = {"R", "G", "B", "A", "T", "knot"};

struct BakedGrid {
    int width = 0, height = 0, depth = 1;
    std::vector<float> data;  ///< channel-interleaved, x fastest, then y (row 0 first), then z
    /// Tree-space position of sample (i, j, k) = origin + i*stepX + j*stepY + k*stepZ.
    Vec3 origin, stepX, stepY, stepZ;
    std::map<std::string, std::string> metadata;

    static constexpr int kChannels = static_cast<int>(kBakeChannels.size());
    size_t sampleCount() const { return size_t(width) * height * depth; }
    float* at(int i, int j, int k = 0) {
        return &data[((size_t(k) * height + j) * width + i) * kChannels];
    }
    const float* at(int i, int j, int k = 0) const {
        return &data[((size_t(k) * height + j) * width + i) * kChannels];
    }
};

}  // namespace nenrin
