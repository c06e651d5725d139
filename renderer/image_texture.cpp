#include "renderer/image_texture.h"

#include <fmt/format.h>

#include <cmath>

#include "grain/cielab.h"
#include "renderer/image_file.h"
#include "util/input_error.h"

namespace nenrin {

ImageTexture ImageTexture::load(const std::string& path, int channels, TextureValues values) {
    const ImageFile image = readImageFile(path);
    const bool decode = values == TextureValues::Colour && !image.floatingPoint;
    struct {
        int width, height, nchannels;
    } spec{image.width, image.height, image.channels};
    const std::vector<float>& all = image.pixels;
    ImageTexture t;
    t.width_ = spec.width;
    t.height_ = spec.height;
    t.channels_ = channels;
    t.texels_.resize(size_t(spec.width) * spec.height * channels);
    for (size_t i = 0; i < size_t(spec.width) * spec.height; ++i) {
        for (int c = 0; c < channels; ++c) {
            float v = all[i * spec.nchannels + std::min(c, spec.nchannels - 1)];
            if (!std::isfinite(v))
                throw InputError(path,
                                 fmt::format("pixel ({}, {})", i % spec.width, i / spec.width),
                                 "expected finite values");
            t.texels_[i * channels + c] = decode ? float(linearFromSrgb(v)) : v;
        }
    }
    return t;
}

void ImageTexture::lookup(double u, double v, float* out) const {
    // Continuous texel coordinates with centres at integers; row 0 is v = 1.
    double x = u * width_ - 0.5, y = (1 - v) * height_ - 0.5;
    double fx = std::floor(x), fy = std::floor(y);
    double ax = x - fx, ay = y - fy;
    auto wrap = [](long long i, int n) { return static_cast<int>(((i % n) + n) % n); };
    int x0 = wrap(static_cast<long long>(fx), width_),
        x1 = wrap(static_cast<long long>(fx) + 1, width_);
    int y0 = wrap(static_cast<long long>(fy), height_),
        y1 = wrap(static_cast<long long>(fy) + 1, height_);
    for (int c = 0; c < channels_; ++c) {
        auto at = [&](int xx, int yy) {
            return texels_[(size_t(yy) * width_ + xx) * channels_ + c];
        };
        double top = at(x0, y0) * (1 - ax) + at(x1, y0) * ax;
        double bottom = at(x0, y1) * (1 - ax) + at(x1, y1) * ax;
        out[c] = static_cast<float>(top * (1 - ay) + bottom * ay);
    }
}

Vec3 ImageTexture::lookup3(double u, double v) const {
    float c[4] = {0, 0, 0, 0};
    lookup(u, v, c);
    return {c[0], c[1], c[2]};
}

}  // namespace nenrin
