#include "renderer/exr_file.h"

// OpenEXR itself rather than OpenImageIO: OpenImageIO pulls some 260 shared libraries (video,
// camera raw, DICOM codecs) into every process, which a cluster pays once per task. Files are
// written with OpenEXRCore (the C API: it takes chunks compressed by the caller, here by
// libdeflate) and read with the C++ API.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/openexr.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstring>
#include <exception>
#include <span>

#include "renderer/exr_zip.h"
#include "renderer/finite_output.h"
#include "util/input_error.h"

namespace nenrin {

namespace {

static_assert(std::endian::native == std::endian::little,
              "EXR samples are little-endian and are packed here as they lie in memory");

/// The file an EXR is written to through OpenEXRCore, and the first error met writing it.
/// While it exists it is the calling thread's current stream: OpenEXRCore reports errors to a
/// callback while it holds the context's lock, so the callback cannot ask the context for its
/// user data (exr_get_user_data takes the same lock: a deadlock).
class ExrStream {
public:
    ExrStream(const std::string& writePath, const std::string& finalPath)
        : finalPath_(finalPath),
          fd_(::open(writePath.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666)),
          outer_(current_) {
        if (fd_ < 0)
            throw InputError(finalPath, "output",
                             std::string("cannot open it for writing: ") + std::strerror(errno));
        current_ = this;
    }
    ~ExrStream() {
        current_ = outer_;
        if (fd_ >= 0) ::close(fd_);
    }
    ExrStream(const ExrStream&) = delete;
    ExrStream& operator=(const ExrStream&) = delete;

    /// Throws InputError for a failed OpenEXRCore call.
    void check(exr_result_t result) const {
        if (result == EXR_ERR_SUCCESS) return;
        throw InputError(
            finalPath_, "output",
            "could not write the EXR: " +
                (error_.empty() ? std::string(exr_get_default_error_message(result)) : error_));
    }
    /// Closes the file; a failure (a full disk on some file systems) throws InputError.
    void close() {
        const int fd = fd_;
        fd_ = -1;
        if (::close(fd) != 0) {
            note(std::strerror(errno));
            check(EXR_ERR_WRITE_IO);
        }
    }

    static int64_t writeAt(exr_const_context_t, void* user, const void* buffer, uint64_t size,
                           uint64_t offset, exr_stream_error_func_ptr_t) noexcept {
        auto* self = static_cast<ExrStream*>(user);
        const char* bytes = static_cast<const char*>(buffer);
        for (uint64_t done = 0; done < size;) {
            const ssize_t n = ::pwrite(self->fd_, bytes + done, size - done, off_t(offset + done));
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) {
                self->note(std::strerror(n < 0 ? errno : ENOSPC));
                return -1;
            }
            done += uint64_t(n);
        }
        return int64_t(size);
    }
    static void onError(exr_const_context_t, exr_result_t, const char* message) noexcept {
        if (current_) current_->note(message);
    }

private:
    /// Keeps the first error's text (called from OpenEXRCore's C frames: must not throw).
    void note(const char* message) noexcept {
        if (!error_.empty() || !message) return;
        try {
            error_ = message;
        } catch (...) {
        }
    }

    static thread_local ExrStream* current_;
    std::string finalPath_;
    int fd_;
    ExrStream* outer_;
    std::string error_;
};

thread_local ExrStream* ExrStream::current_ = nullptr;

/// One thread's buffers for the blocks of an EXR: rows packed as OpenEXR lays them out, then
/// compressed.
class BlockPacker {
public:
    /// Rows [r0, r1) of the band (each row: every channel of `order` in turn), compressed.
    std::span<const uint8_t> pack(const std::vector<const ExrChannel*>& order, int width, int r0,
                                  int r1) {
        packed_.resize(size_t(r1 - r0) * order.size() * width * sizeof(float));
        auto* out = reinterpret_cast<float*>(packed_.data());
        for (int r = r0; r < r1; ++r)
            for (const ExrChannel* c : order) {
                const float* in = c->values + size_t(r) * width * c->stride;
                if (c->stride == 1)
                    out = std::copy(in, in + width, out);
                else
                    for (int i = 0; i < width; ++i) *out++ = in[size_t(i) * c->stride];
            }
        return compressor_.compress(packed_);
    }

private:
    std::vector<uint8_t> packed_;
    ExrZipCompressor compressor_;
};

}  // namespace

void writeFloatExr(const std::string& finalPath, const std::string& writePath, int width,
                   int height, const std::vector<std::string>& channels, const float* pixels,
                   const std::map<std::string, std::string>& metadata, RowBand band,
                   ExrValues values, int threads) {
    std::vector<ExrChannel> planes;
    for (size_t c = 0; c < channels.size(); ++c)
        planes.push_back({channels[c], pixels + c, channels.size()});
    writeFloatExrChannels(finalPath, writePath, width, height, planes, metadata, band, values,
                          threads);
}

void writeFloatExrChannels(const std::string& finalPath, const std::string& writePath, int width,
                           int height, const std::vector<ExrChannel>& channels,
                           const std::map<std::string, std::string>& metadata, RowBand band,
                           ExrValues values, int threads) {
    const int end = band.end < 0 ? height : band.end;
    const size_t samples = size_t(end - band.begin) * width;
    for (const ExrChannel& c : channels)
        requireFiniteChannel(c.values, c.stride, samples, c.name, width, band.begin, finalPath);
    ExrStream stream(writePath, finalPath);
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = &ExrStream::onError;
    init.user_data = &stream;
    init.write_fn = &ExrStream::writeAt;
    exr_context_t context = nullptr;
    stream.check(exr_start_write(&context, writePath.c_str(), EXR_WRITE_FILE_DIRECTLY, &init));
    // Finished (its chunk offset table written) or, on an error, released.
    struct Finish {
        exr_context_t& context;
        ~Finish() {
            if (context) exr_finish(&context);
        }
    } finish{context};
    // Names over 31 characters (a long metadata key) need the long-name flag, as OpenEXR's
    // C++ writer sets it by itself.
    stream.check(exr_set_longname_support(context, 1));
    int part = 0;
    stream.check(exr_add_part(context, "", EXR_STORAGE_SCANLINE, &part));
    const exr_attr_box2i_t display{{0, 0}, {width - 1, height - 1}};
    const exr_attr_box2i_t data{{0, band.begin}, {width - 1, end - 1}};
    const exr_attr_v2f_t centre{0, 0};
    stream.check(exr_initialize_required_attr(context, part, &display, &data, 1.0f, &centre, 1.0f,
                                              EXR_LINEORDER_INCREASING_Y, EXR_COMPRESSION_ZIP));
    for (const ExrChannel& c : channels)
        stream.check(exr_add_channel(context, part, c.name.c_str(), EXR_PIXEL_FLOAT,
                                     EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1));
    if (values == ExrValues::SceneLinear)
        stream.check(exr_attr_set_string(context, part, "oiio:ColorSpace", "Linear"));
    else
        stream.check(exr_attr_set_string(context, part, "colorInteropID", "data"));
    for (const auto& [key, value] : metadata)
        stream.check(exr_attr_set_string(context, part, ("nenrin:" + key).c_str(), value.c_str()));
    stream.check(exr_write_header(context));

    // The channels in the file's order (sorted by name), as each row of a block packs them.
    const exr_attr_chlist_t* list = nullptr;
    stream.check(exr_get_channels(context, part, &list));
    std::vector<const ExrChannel*> order;
    for (int i = 0; i < list->num_channels; ++i)
        for (const ExrChannel& c : channels)
            if (c.name == list->entries[i].name.str) order.push_back(&c);
    if (order.size() != channels.size())
        throw InputError(finalPath, "output", "two channels of the EXR share a name");
    int32_t rowsPerBlock = 0;
    stream.check(exr_get_scanlines_per_chunk(context, part, &rowsPerBlock));
    const int blocks = (end - band.begin + rowsPerBlock - 1) / rowsPerBlock;
    // Blocks are compressed in batches (side by side with threads > 1), then written in order:
    // the bytes do not depend on the thread count. A batch holds at most ~64 MB of blocks.
    const size_t blockBytes = size_t(rowsPerBlock) * width * channels.size() * sizeof(float);
    const int batch = static_cast<int>(std::clamp<size_t>(
        (size_t(64) << 20) / std::max<size_t>(blockBytes, 1), 1, size_t(std::max(1, threads)) * 8));
    std::vector<std::vector<uint8_t>> stored(static_cast<size_t>(batch));
    tbb::enumerable_thread_specific<BlockPacker> packers;
    tbb::task_arena arena(std::max(1, threads));
    for (int first = 0; first < blocks; first += batch) {
        const int count = std::min(batch, blocks - first);
        auto compressBlock = [&](int k) {
            const int y0 = band.begin + (first + k) * rowsPerBlock;
            const int y1 = std::min(end, y0 + rowsPerBlock);
            BlockPacker& packer = packers.local();
            const auto bytes = packer.pack(order, width, y0 - band.begin, y1 - band.begin);
            stored[size_t(k)].assign(bytes.begin(), bytes.end());
        };
        if (threads > 1)
            arena.execute([&] { tbb::parallel_for(0, count, compressBlock); });
        else
            for (int k = 0; k < count; ++k) compressBlock(k);
        for (int k = 0; k < count; ++k)
            stream.check(
                exr_write_scanline_chunk(context, part, band.begin + (first + k) * rowsPerBlock,
                                         stored[size_t(k)].data(), stored[size_t(k)].size()));
    }
    // The chunk offset table is written here.
    stream.check(exr_finish(&context));
    stream.close();
}

FloatExr readFloatExr(const std::string& path) {
    FloatExr exr;
    try {
        Imf::InputFile file(path.c_str());
        const Imf::Header& header = file.header();
        const Imath::Box2i display = header.displayWindow(), data = header.dataWindow();
        const long long fullWidth = static_cast<long long>(display.max.x) - display.min.x + 1;
        const long long fullHeight = static_cast<long long>(display.max.y) - display.min.y + 1;
        if (display.min.x != 0 || display.min.y != 0 || data.min.x != 0 ||
            data.max.x != display.max.x || data.min.y < 0 || data.max.y >= fullHeight ||
            data.max.y < data.min.y || fullWidth > (1 << 20) || fullHeight > (1 << 20))
            throw InputError(
                path, "",
                fmt::format("expected a band of whole rows of the frame, found data "
                            "window ({}, {})..({}, {}) in display window ({}, "
                            "{})..({}, {})",
                            data.min.x, data.min.y, data.max.x, data.max.y, display.min.x,
                            display.min.y, display.max.x, display.max.y));
        exr.width = static_cast<int>(fullWidth);
        exr.height = static_cast<int>(fullHeight);
        exr.band = {data.min.y, data.max.y + 1};
        for (auto it = header.channels().begin(); it != header.channels().end(); ++it)
            exr.channels.push_back(it.name());
        for (auto it = header.begin(); it != header.end(); ++it) {
            const std::string name = it.name();
            auto* text = dynamic_cast<const Imf::StringAttribute*>(&it.attribute());
            if (name.rfind("nenrin:", 0) == 0 && text) exr.metadata[name.substr(7)] = text->value();
        }
        const size_t rows = size_t(exr.band.end - exr.band.begin);
        if (double(exr.width) * double(rows) * double(exr.channels.size()) > double(1u << 30))
            throw InputError(path, "",
                             fmt::format("{}x{} pixels of {} channels: over the limit of 2^30 "
                                         "values",
                                         exr.width, rows, exr.channels.size()));
        const size_t stride = exr.channels.size() * sizeof(float);
        exr.pixels.resize(size_t(exr.width) * rows * exr.channels.size());
        char* base =
            reinterpret_cast<char*>(exr.pixels.data()) -
            static_cast<ptrdiff_t>(exr.band.begin) * exr.width * static_cast<ptrdiff_t>(stride);
        Imf::FrameBuffer frame;
        for (size_t c = 0; c < exr.channels.size(); ++c)
            frame.insert(exr.channels[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), stride,
                                                     stride * exr.width));
        file.setFrameBuffer(frame);
        file.readPixels(data.min.y, data.max.y);
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw InputError(path, "",
                         std::string("cannot read the EXR (damaged or not an EXR?): ") + e.what());
    }
    return exr;
}

void orderChannels(FloatExr& exr, const std::vector<std::string>& order, const std::string& path) {
    if (exr.channels == order) return;
    std::vector<std::string> sorted = exr.channels, wanted = order;
    std::sort(sorted.begin(), sorted.end());
    std::sort(wanted.begin(), wanted.end());
    if (sorted != wanted)
        throw InputError(path, "channels",
                         fmt::format("expected {}, found {}", fmt::join(order, ","),
                                     fmt::join(exr.channels, ",")));
    std::vector<size_t> from(order.size());
    for (size_t c = 0; c < order.size(); ++c)
        from[c] = static_cast<size_t>(
            std::find(exr.channels.begin(), exr.channels.end(), order[c]) - exr.channels.begin());
    const size_t n = order.size();
    std::vector<float> pixel(n);
    for (size_t i = 0; i + n <= exr.pixels.size(); i += n) {
        for (size_t c = 0; c < n; ++c) pixel[c] = exr.pixels[i + from[c]];
        std::copy(pixel.begin(), pixel.end(), exr.pixels.begin() + i);
    }
    exr.channels = order;
}

}  // namespace nenrin
