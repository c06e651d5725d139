#include "renderer/png_file.h"

#include <fmt/format.h>
#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <memory>

#include "util/input_error.h"

namespace nenrin {

namespace {

struct FileCloser {
    void operator()(FILE* f) const {
        if (f) std::fclose(f);
    }
};
using File = std::unique_ptr<FILE, FileCloser>;

/// libpng reports errors through longjmp; the message is kept for the InputError.
void onError(png_structp png, png_const_charp message) {
    auto* text = static_cast<std::string*>(png_get_error_ptr(png));
    *text = message;
    png_longjmp(png, 1);
}
void onWarning(png_structp, png_const_charp) {}

}  // namespace

void writePng8(const std::string& finalPath, const std::string& writePath, int width, int height,
               const std::vector<uint8_t>& rgb, const std::map<std::string, std::string>& text,
               PngValues values) {
    File file(std::fopen(writePath.c_str(), "wb"));
    if (!file) throw InputError(finalPath, "", "cannot create the PNG");
    std::string error;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, onError, onWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!info) {
        png_destroy_write_struct(&png, nullptr);
        throw std::bad_alloc();
    }
    std::vector<png_text> chunks;
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        throw InputError(finalPath, "", "cannot write the PNG: " + error);
    }
    png_init_io(png, file.get());
    png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
                 PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    if (values == PngValues::SrgbColour)
        png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    for (const auto& [key, value] : text) {
        png_text t{};
        t.compression = PNG_TEXT_COMPRESSION_NONE;
        t.key = const_cast<char*>(key.c_str());
        t.text = const_cast<char*>(value.c_str());
        chunks.push_back(t);
    }
    if (!chunks.empty()) png_set_text(png, info, chunks.data(), static_cast<int>(chunks.size()));
    png_write_info(png, info);
    for (int y = 0; y < height; ++y)
        png_write_row(png, const_cast<png_bytep>(&rgb[size_t(y) * width * 3]));
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    if (std::fflush(file.get()) != 0 || std::ferror(file.get()) || std::fclose(file.release()) != 0)
        throw InputError(finalPath, "", "cannot write the PNG (disk full?)");
}

ImageFile readPng(const std::string& path) {
    File file(std::fopen(path.c_str(), "rb"));
    if (!file) throw InputError(path, "", "cannot open the PNG");
    std::string error;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, onError, onWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!info) {
        png_destroy_read_struct(&png, nullptr, nullptr);
        throw std::bad_alloc();
    }
    ImageFile image;
    std::vector<uint8_t> rows;
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        throw InputError(path, "", "cannot read the PNG (damaged?): " + error);
    }
    png_init_io(png, file.get());
    png_set_user_limits(png, 1 << 15, 1 << 15);
    png_read_info(png, info);
    const int depth = png_get_bit_depth(png, info), type = png_get_color_type(png, info);
    // Everything to 8 or 16 bits per channel, grey / grey+alpha / RGB / RGBA.
    if (type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
    if (type == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
    if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
    if (depth == 16) png_set_swap(png);  // PNG is big-endian; read native uint16
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    image.width = static_cast<int>(png_get_image_width(png, info));
    image.height = static_cast<int>(png_get_image_height(png, info));
    image.channels = png_get_channels(png, info);
    const bool wide = png_get_bit_depth(png, info) == 16;
    const size_t rowBytes = png_get_rowbytes(png, info);
    rows.resize(rowBytes * image.height);
    std::vector<png_bytep> rowPointers(image.height);
    for (int y = 0; y < image.height; ++y) rowPointers[y] = &rows[rowBytes * y];
    png_read_image(png, rowPointers.data());
    png_read_end(png, nullptr);
    png_destroy_read_struct(&png, &info, nullptr);

    static const std::vector<std::vector<std::string>> kNames = {
        {}, {"Y"}, {"Y", "A"}, {"R", "G", "B"}, {"R", "G", "B", "A"}};
    image.channelNames = kNames.at(size_t(image.channels));
    const size_t values = size_t(image.width) * image.height * image.channels;
    image.pixels.resize(values);
    for (size_t i = 0; i < values; ++i)
        image.pixels[i] = wide ? reinterpret_cast<const uint16_t*>(rows.data())[i] * (1.0f / 65535)
                               : rows[i] * (1.0f / 255);
    return image;
}

}  // namespace nenrin
