#include "renderer/exr_file.h"

// OpenEXR itself rather than OpenImageIO: OpenImageIO pulls some 260 shared libraries (video,
// camera raw, DICOM codecs) into every process, which a cluster pays once per task.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <exception>
#include <fstream>

#include "renderer/finite_output.h"
#include "util/input_error.h"

namespace nenrin {

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
    const Imath::Box2i display({0, 0}, {width - 1, height - 1});
    const Imath::Box2i data({0, band.begin}, {width - 1, end - 1});
    // zip at level 1: nearly the size of the default level, at a fraction of the time.
    Imf::Header header(display, data, 1, Imath::V2f(0, 0), 1, Imf::INCREASING_Y,
                       Imf::ZIP_COMPRESSION);
    header.zipCompressionLevel() = 1;
    if (values == ExrValues::SceneLinear)
        header.insert("oiio:ColorSpace", Imf::StringAttribute("Linear"));
    else
        header.insert("colorInteropID", Imf::StringAttribute("data"));
    for (const auto& [key, value] : metadata)
        header.insert("nenrin:" + key, Imf::StringAttribute(value));
    Imf::FrameBuffer frame;
    for (const ExrChannel& c : channels) {
        const size_t stride = c.stride * sizeof(float);
        // The frame buffer is addressed by absolute pixel position: the band's first row is
        // values[0], so the base pointer is moved back by band.begin rows (never dereferenced).
        const char* base =
            reinterpret_cast<const char*>(c.values) -
            static_cast<ptrdiff_t>(band.begin) * width * static_cast<ptrdiff_t>(stride);
        header.channels().insert(c.name, Imf::Channel(Imf::FLOAT));
        frame.insert(c.name,
                     Imf::Slice(Imf::FLOAT, const_cast<char*>(base), stride, stride * width));
    }
    // Our own stream, so that the last writes (the line offsets, written when the file object
    // is destroyed, where OpenEXR cannot report an error) are checked when it is closed.
    std::ofstream stream(writePath, std::ios::binary | std::ios::trunc);
    try {
        Imf::StdOFStream out(stream, writePath.c_str());
        // Each block of 16 rows is compressed on its own, so the blocks can be compressed
        // side by side: at two threads, the write of a 512 x 512 render was a quarter of its
        // time.
        if (threads > 1 && Imf::globalThreadCount() < threads) Imf::setGlobalThreadCount(threads);
        Imf::OutputFile file(out, header, threads > 1 ? threads : 0);
        file.setFrameBuffer(frame);
        file.writePixels(end - band.begin);
    } catch (const std::exception& e) {
        throw InputError(finalPath, "output",
                         std::string("could not write the EXR (disk full?): ") + e.what());
    }
    stream.close();
    if (!stream) throw InputError(finalPath, "output", "could not write the EXR (disk full?)");
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
