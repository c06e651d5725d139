#include "renderer/exr_file.h"

#include <OpenImageIO/imageio.h>

#include "util/input_error.h"

namespace nenrin {

void writeFloatExr(const std::string& finalPath, const std::string& writePath, int width,
                   int height, const std::vector<std::string>& channels, const float* pixels,
                   const std::map<std::string, std::string>& metadata) {
    OIIO::ImageSpec spec(width, height, static_cast<int>(channels.size()), OIIO::TypeDesc::FLOAT);
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

}  // namespace nenrin
