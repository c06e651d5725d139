#pragma once
/// Reading images (textures, environment maps, colour strips, images to compare) as float.
/// EXR goes through OpenEXR and PNG through libpng, linked in; every other format (JPEG, TIFF,
/// HDR, ...) through OpenImageIO in a module (nenrin_oiio_reader) loaded on first use, so that
/// a process that never meets such a file never loads OpenImageIO's ~260 libraries.

#include <string>
#include <vector>

namespace nenrin {

struct ImageFile {
    int width = 0, height = 0, channels = 0;
    /// R, G, B, A first where present (else Y, A for grey), then any other channels.
    std::vector<std::string> channelNames;
    std::vector<float> pixels;   ///< channel-interleaved, row 0 at the top
    bool floatingPoint = false;  ///< stored as float or half (linear); else integers (display)
};

/// Reads the image's data window (its first part, its first subimage). Throws InputError
/// naming `path` if it cannot be read, is deep, or holds more than 2^30 values.
ImageFile readImageFile(const std::string& path);

/// `image` resampled to width x height by OpenImageIO's ImageBufAlgo::resize with the named
/// filter ("lanczos3", "triangle", ...: OpenImageIO widens it by the factor when shrinking, an
/// antialiasing filter), through the OpenImageIO module. Throws InputError naming `path`.
ImageFile resizeImageFile(const ImageFile& image, int width, int height, const std::string& filter,
                          const std::string& path);

/// The C interface of the OpenImageIO module (renderer/oiio_reader).
extern "C" {
typedef struct NenrinOiioImage {
    int width, height, channels, floatingPoint;
    float* pixels;     ///< malloc'ed by the module; free with nenrin_oiio_free
    char names[1024];  ///< channel names, comma-separated (truncated if longer)
} NenrinOiioImage;
/// 0 on success, else a message in `error`.
typedef int (*NenrinOiioReadFn)(const char* path, NenrinOiioImage* image, char* error,
                                unsigned long errorSize);
typedef void (*NenrinOiioFreeFn)(NenrinOiioImage* image);
/// Resizes channel-interleaved `pixels` into `out` (outWidth x outHeight x channels floats,
/// allocated by the caller); 0 on success, else a message in `error`.
typedef int (*NenrinOiioResizeFn)(const float* pixels, int width, int height, int channels,
                                  const char* filter, int outWidth, int outHeight, float* out,
                                  char* error, unsigned long errorSize);
}

}  // namespace nenrin
