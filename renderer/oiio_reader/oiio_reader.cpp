// The OpenImageIO module: reads any image format OpenImageIO knows, for the formats nenrin does
// not read itself, and resizes images with its filters (renderer/image_file.h). A shared module
// loaded on first use, so that OpenImageIO's ~260 libraries are loaded only by processes that meet
// such a file.

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <cstdlib>
#include <cstring>
#include <string>

#include "renderer/image_file.h"

namespace {

void copyError(const std::string& message, char* error, unsigned long size) {
    if (size == 0) return;
    std::strncpy(error, message.c_str(), size - 1);
    error[size - 1] = '\0';
}

}  // namespace

extern "C" __attribute__((visibility("default"))) int nenrin_oiio_read(
    const char* path, nenrin::NenrinOiioImage* image, char* error, unsigned long errorSize) {
    try {
        auto in = OIIO::ImageInput::open(path);
        if (!in) {
            copyError(OIIO::geterror(), error, errorSize);
            return 1;
        }
        const OIIO::ImageSpec spec = in->spec();
        const double values = double(spec.width) * spec.height * spec.depth * spec.nchannels;
        if (spec.deep || spec.depth != 1 || spec.nchannels < 1 || values > double(1u << 30)) {
            copyError("expected a flat 2D image of at most 2^30 values", error, errorSize);
            return 1;
        }
        auto* pixels = static_cast<float*>(std::malloc(sizeof(float) * size_t(values)));
        if (!pixels) {
            copyError("out of memory", error, errorSize);
            return 1;
        }
        if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels)) {
            std::free(pixels);
            copyError(in->geterror(), error, errorSize);
            return 1;
        }
        image->width = spec.width;
        image->height = spec.height;
        image->channels = spec.nchannels;
        image->floatingPoint = spec.format.is_floating_point() ? 1 : 0;
        image->pixels = pixels;
        std::string names;
        for (const std::string& n : spec.channelnames) names += (names.empty() ? "" : ",") + n;
        copyError(names, image->names, sizeof image->names);
        return 0;
    } catch (const std::exception& e) {
        copyError(e.what(), error, errorSize);
        return 1;
    }
}

extern "C" __attribute__((visibility("default"))) void nenrin_oiio_free(
    nenrin::NenrinOiioImage* image) {
    std::free(image->pixels);
    image->pixels = nullptr;
}

extern "C" __attribute__((visibility("default"))) int nenrin_oiio_resize(
    const float* pixels, int width, int height, int channels, const char* filter, int outWidth,
    int outHeight, float* out, char* error, unsigned long errorSize) {
    try {
        // Both buffers wrapped, not copied: the caller owns them.
        const OIIO::ImageBuf src(OIIO::ImageSpec(width, height, channels, OIIO::TypeDesc::FLOAT),
                                 const_cast<float*>(pixels));
        OIIO::ImageBuf dst(OIIO::ImageSpec(outWidth, outHeight, channels, OIIO::TypeDesc::FLOAT),
                           out);
        if (!OIIO::ImageBufAlgo::resize(dst, src, filter)) {
            copyError(dst.geterror(), error, errorSize);
            return 1;
        }
        return 0;
    } catch (const std::exception& e) {
        copyError(e.what(), error, errorSize);
        return 1;
    }
}
