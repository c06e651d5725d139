#pragma once
/// Images as the wood-photo statistics see them: resampled to 256 x 256 the way the team's
/// photo-stats script does it (with PIL), so that every figure is taken at one scale (a 5 cm
/// face then has 0.2 mm pixels).

#include <array>
#include <string>

#include "renderer/stats/ndimage_filters.h"

namespace nenrin {

/// The side of the square every image is resampled to.
constexpr int kStatsSize = 256;
/// The smallest image taken: smaller ones hold nothing at the scales the figures measure.
constexpr int kStatsMinimumSide = 16;

/// An image's R, G, B at 256 x 256, scene-linear, and the size it had in its file.
struct StatsRgb {
    int sourceWidth = 0, sourceHeight = 0;
    std::array<Plane, 3> linear;
};

/// Reads `path`. Integer images (PNG, JPEG, ...) are sRGB: resampled in their encoding with
/// lanczos3 and rounded to 8 bits (PIL's LANCZOS on an 8-bit image), then decoded; grey images
/// count as R = G = B. Float images (EXR) are linear: R, G, B clipped at 0, resampled with a
/// triangle filter (PIL's BILINEAR). An image that is already 256 x 256 is taken as it is, as
/// PIL does; other sizes go through OpenImageIO's resize, which is close to PIL's but not
/// equal (docs/stats.md). Throws InputError naming `path`: unreadable, a float image without
/// R, G, B, a value that is not finite, or a side under kStatsMinimumSide.
StatsRgb readStatsRgb(const std::string& path);

/// One channel of an image by name (the growth time T of a bake), at 256 x 256.
struct StatsChannel {
    int sourceWidth = 0, sourceHeight = 0;
    Plane values;
};

/// Reads channel `name` of `path`, resampled as float images are (triangle), not clipped.
/// Throws InputError naming `path` if the channel is missing or not finite, or the image too
/// small.
StatsChannel readStatsChannel(const std::string& path, const std::string& name);

/// L*, a*, b* planes of scene-linear R, G, B planes (photo_lab.h).
std::array<Plane, 3> labPlanes(const std::array<Plane, 3>& linear);

}  // namespace nenrin
