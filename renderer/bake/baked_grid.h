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
    /// A slice's plane normal (any length; the side the image is seen from), for the
    /// end-grain term; zero for volumes, whose samples lie inside the wood.
    Vec3 normal;
    std::map<std::string, std::string> metadata;
    /// The layers held: all of them, unless a split job (--tile) bakes a band. A layer is a
    /// row of a 2D grid or a z slice of a volume; data holds layers [layerBegin, layerEnd).
    int layerBegin = 0, layerEnd = -1;

    static constexpr int kChannels = static_cast<int>(kBakeChannels.size());
    bool isVolume() const { return depth > 1; }
    int layerCount() const { return isVolume() ? depth : height; }
    int storedEnd() const { return layerEnd < 0 ? layerCount() : layerEnd; }
    size_t layerSize() const { return isVolume() ? size_t(width) * height : size_t(width); }
    bool whole() const { return layerBegin == 0 && storedEnd() == layerCount(); }
    /// Samples held (all of the grid's unless it is a band).
    size_t sampleCount() const { return layerSize() * (storedEnd() - layerBegin); }
    float* at(int i, int j, int k = 0) { return &data[index(i, j, k) * kChannels]; }
    const float* at(int i, int j, int k = 0) const { return &data[index(i, j, k) * kChannels]; }

private:
    size_t index(int i, int j, int k) const {
        return (size_t(k) * height + j) * width + i - size_t(layerBegin) * layerSize();
    }
};

}  // namespace nenrin
