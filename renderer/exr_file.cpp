#include "renderer/exr_file.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "util/input_error.h"

namespace nenrin {

void writeFloatExr(const std::string& finalPath, const std::string& writePath, int width,
                   int height, const std::vector<std::string>& channels, const float* pixels,
                   const std::map<std::string, std::string>& metadata, RowBand band) {
    const int end = band.end < 0 ? height : band.end;
    OIIO::ImageSpec spec(width, end - band.begin, static_cast<int>(channels.size()),
                         OIIO::TypeDesc::FLOAT);
    if (band.begin != 0 || end != height) {
        spec.y = band.begin;
        spec.full_x = spec.full_y = 0;
        spec.full_width = width;
        spec.full_height = height;
    }
    spec.channelnames = channels;
    for (size_t c = 0; c < channels.size(); ++c)
        if (channels[c] == "A") spec.alpha_channel = static_cast<int>(c);
    // zip at level 1: nearly the size of the default level, at a fraction of the time.
    spec.attribute("compression", "zip:1");
    spec.attribute("oiio:ColorSpace", "Linear");
    // OpenEXR would stamp the current time: a fixed date keeps the bytes reproducible.
    spec.attribute("DateTime", "2000:01:01 00:00:00");
    for (const auto& [key, value] : metadata) spec.attribute("nenrin:" + key, value);
    auto writer = OIIO::ImageOutput::create(writePath);
    if (!writer || !writer->open(writePath, spec) ||
        !writer->write_image(OIIO::TypeDesc::FLOAT, pixels) || !writer->close())
        throw InputError(
            finalPath, "output",
            "could not write the EXR: " + (writer ? writer->geterror() : OIIO::geterror()));
}

FloatExr readFloatExr(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw InputError(path, "", "cannot read the EXR: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    if (in->format_name() != std::string("openexr"))
        throw InputError(path, "",
                         std::string("expected an OpenEXR file, found ") + in->format_name());
    if (spec.deep || spec.depth != 1 || spec.full_x != 0 || spec.full_y != 0 || spec.x != 0 ||
        spec.width != spec.full_width || spec.y < 0 || spec.y + spec.height > spec.full_height ||
        spec.height <= 0)
        throw InputError(path, "",
                         fmt::format("expected a band of whole rows of the frame, found data "
                                     "window {},{} {}x{} in a {}x{} frame",
                                     spec.x, spec.y, spec.width, spec.height, spec.full_width,
                                     spec.full_height));
    FloatExr exr;
    exr.width = spec.full_width;
    exr.height = spec.full_height;
    exr.band = {spec.y, spec.y + spec.height};
    exr.channels = spec.channelnames;
    for (const OIIO::ParamValue& p : spec.extra_attribs) {
        const std::string name = p.name().string();
        if (name.rfind("nenrin:", 0) == 0 && p.type() == OIIO::TypeDesc::STRING)
            exr.metadata[name.substr(7)] = p.get_string();
    }
    exr.pixels.resize(size_t(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, exr.pixels.data()))
        throw InputError(path, "",
                         "cannot read the EXR's pixels (truncated or damaged?): " + in->geterror());
    return exr;
}

}  // namespace nenrin

namespace nenrin {

void orderChannels(FloatExr& exr, const std::vector<std::string>& order, const std::string& path) {
    if (exr.channels == order) return;
    std::vector<size_t> from(order.size());
    std::vector<std::string> sorted = exr.channels, wanted = order;
    std::sort(sorted.begin(), sorted.end());
    std::sort(wanted.begin(), wanted.end());
    if (sorted != wanted)
        throw InputError(path, "channels",
                         fmt::format("expected {}, found {}", fmt::join(order, ","),
                                     fmt::join(exr.channels, ",")));
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
