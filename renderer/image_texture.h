#pragma once
/// A float image read with OpenImageIO and looked up bilinearly by texture coordinates
/// (u right, v up: v = 1 is the image's top row, as OBJ files and nenrin's UV bakes have it;
/// texel centres at (i + 0.5) / W), wrapping around at the borders.

#include <string>
#include <vector>

#include "util/vec3.h"

namespace nenrin {

/// What a texture's values are: colour (an 8- or 16-bit image holds sRGB-encoded values, made
/// linear on reading; float images are linear already) or data (normals, directions: as read).
enum class TextureValues { Colour, Data };

class ImageTexture {
public:
    /// Reads the first `channels` channels (a grey image is repeated). Throws InputError for a
    /// missing or unreadable file, or one with non-finite texels.
    static ImageTexture load(const std::string& path, int channels,
                             TextureValues values = TextureValues::Data);

    /// Bilinear lookup; fills `channels()` values.
    void lookup(double u, double v, float* out) const;
    Vec3 lookup3(double u, double v) const;
    int channels() const { return channels_; }

private:
    int width_ = 0, height_ = 0, channels_ = 0;
    std::vector<float> texels_;
};

}  // namespace nenrin
