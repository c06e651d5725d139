#include "renderer/exr_zip.h"

#include <libdeflate.h>

#include <new>

namespace nenrin {

namespace {

/// libdeflate's level 1 compressed a 512 x 512 film to 1 % less than zlib's level 1 (what
/// nenrin asked OpenEXR for), in about half the time; higher levels gained under 1 % more.
constexpr int kLevel = 1;

}  // namespace

ExrZipCompressor::ExrZipCompressor() : compressor_(libdeflate_alloc_compressor(kLevel)) {
    if (!compressor_) throw std::bad_alloc();
}

ExrZipCompressor::~ExrZipCompressor() { libdeflate_free_compressor(compressor_); }

std::span<const uint8_t> ExrZipCompressor::compress(std::span<const uint8_t> packed) {
    const size_t n = packed.size();
    if (n == 0) return packed;
    // Even bytes first, then odd ones (a float's high bytes, sign and exponent, change slowly
    // from sample to sample and end up side by side), each byte replaced by its difference
    // from the one before it in that order, plus 128 (mod 256). Written as differences of the
    // input's bytes, so the loops have no carried dependency and vectorise.
    predicted_.resize(n);
    const uint8_t* in = packed.data();
    uint8_t* out = predicted_.data();
    const size_t half = (n + 1) / 2;
    out[0] = in[0];
    for (size_t i = 1; i < half; ++i)
        out[i] = static_cast<uint8_t>(in[2 * i] - in[2 * i - 2] + 128);
    if (n > 1) out[half] = static_cast<uint8_t>(in[1] - in[2 * (half - 1)] + 128);
    for (size_t i = 1; half + i < n; ++i)
        out[half + i] = static_cast<uint8_t>(in[2 * i + 1] - in[2 * i - 1] + 128);
    compressed_.resize(libdeflate_zlib_compress_bound(compressor_, n));
    const size_t size = libdeflate_zlib_compress(compressor_, predicted_.data(), n,
                                                 compressed_.data(), compressed_.size());
    if (size == 0 || size >= n) return packed;
    return {compressed_.data(), size};
}

}  // namespace nenrin
