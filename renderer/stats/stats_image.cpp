#include "renderer/stats/stats_image.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "grain/cielab.h"
#include "renderer/image_file.h"
#include "renderer/stats/photo_lab.h"
#include "util/input_error.h"

namespace nenrin {

namespace {

int channelIndex(const ImageFile& image, const std::string& name) {
    const auto& names = image.channelNames;
    const auto it = std::find(names.begin(), names.end(), name);
    return it == names.end() ? -1 : int(it - names.begin());
}

std::string channelList(const ImageFile& image) {
    std::string list;
    for (const auto& n : image.channelNames) list += (list.empty() ? "" : ", ") + n;
    return list.empty() ? "none" : list;
}

ImageFile readSized(const std::string& path) {
    ImageFile image = readImageFile(path);
    if (image.width < kStatsMinimumSide || image.height < kStatsMinimumSide)
        throw InputError(path, "",
                         fmt::format("{}x{} pixels: expected at least {}x{} (the statistics are "
                                     "taken at {}x{})",
                                     image.width, image.height, kStatsMinimumSide,
                                     kStatsMinimumSide, kStatsSize, kStatsSize));
    return image;
}

/// The channels `picks` of `image` as a new image, every value checked to be finite.
ImageFile pickChannels(const ImageFile& image, const std::vector<int>& picks,
                       const std::string& path) {
    ImageFile out;
    out.width = image.width;
    out.height = image.height;
    out.channels = int(picks.size());
    out.floatingPoint = image.floatingPoint;
    out.pixels.resize(size_t(image.width) * image.height * picks.size());
    for (size_t i = 0; i < size_t(image.width) * image.height; ++i)
        for (size_t c = 0; c < picks.size(); ++c) {
            const float v = image.pixels[i * image.channels + size_t(picks[c])];
            if (!std::isfinite(v))
                throw InputError(path,
                                 fmt::format("pixel ({}, {})", i % image.width, i / image.width),
                                 fmt::format("channel {} is {}: expected a finite value",
                                             image.channelNames[size_t(picks[c])], v));
            out.pixels[i * picks.size() + c] = v;
        }
    for (int c : picks) out.channelNames.push_back(image.channelNames[size_t(c)]);
    return out;
}

/// R, G, B of an image: by name, or a grey integer image's first channel three times.
std::vector<int> rgbChannels(const ImageFile& image, const std::string& path) {
    std::vector<int> picks{channelIndex(image, "R"), channelIndex(image, "G"),
                           channelIndex(image, "B")};
    if (std::count(picks.begin(), picks.end(), -1) == 0) return picks;
    if (!image.floatingPoint && image.channels >= 3) return {0, 1, 2};
    if (!image.floatingPoint && image.channels >= 1) return {0, 0, 0};
    throw InputError(
        path, "",
        fmt::format("channels {}: expected R, G, B (a linear colour image)", channelList(image)));
}

/// Plane c of a channel-interleaved image.
Plane planeOf(const ImageFile& image, int c) {
    Plane p(image.width, image.height);
    for (size_t i = 0; i < p.values.size(); ++i)
        p.values[i] = image.pixels[i * image.channels + size_t(c)];
    return p;
}

ImageFile resized(const ImageFile& image, const std::string& filter, const std::string& path) {
    if (image.width == kStatsSize && image.height == kStatsSize) return image;  // PIL: unchanged
    return resizeImageFile(image, kStatsSize, kStatsSize, filter, path);
}

}  // namespace

StatsRgb readStatsRgb(const std::string& path) {
    const ImageFile file = readSized(path);
    ImageFile rgb = pickChannels(file, rgbChannels(file, path), path);
    StatsRgb out;
    out.sourceWidth = rgb.width;
    out.sourceHeight = rgb.height;
    if (rgb.floatingPoint) {
        for (float& v : rgb.pixels) v = std::max(v, 0.f);
        rgb = resized(rgb, "triangle", path);
    } else if (rgb.width != kStatsSize || rgb.height != kStatsSize) {
        // PIL resamples the 8-bit encoded values and rounds its result to 8 bits.
        rgb = resized(rgb, "lanczos3", path);
        for (float& v : rgb.pixels) v = std::clamp(std::round(v * 255.f), 0.f, 255.f) / 255.f;
    }
    for (int c = 0; c < 3; ++c) {
        out.linear[size_t(c)] = planeOf(rgb, c);
        if (!rgb.floatingPoint)
            for (double& v : out.linear[size_t(c)].values) v = linearFromSrgb(v);
    }
    return out;
}

StatsChannel readStatsChannel(const std::string& path, const std::string& name) {
    const ImageFile file = readSized(path);
    const int c = channelIndex(file, name);
    if (c < 0)
        throw InputError(path, "",
                         fmt::format("no channel {} (channels: {}): expected a nenrin bake", name,
                                     channelList(file)));
    const ImageFile one = resized(pickChannels(file, {c}, path), "triangle", path);
    return {file.width, file.height, planeOf(one, 0)};
}

std::array<Plane, 3> labPlanes(const std::array<Plane, 3>& linear) {
    std::array<Plane, 3> lab;
    for (Plane& p : lab) p = Plane(linear[0].width, linear[0].height);
    for (size_t i = 0; i < linear[0].values.size(); ++i) {
        const auto v =
            photoLabFromLinear(linear[0].values[i], linear[1].values[i], linear[2].values[i]);
        for (size_t c = 0; c < 3; ++c) lab[c].values[i] = v[c];
    }
    return lab;
}

}  // namespace nenrin
