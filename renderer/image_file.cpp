#include "renderer/image_file.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "renderer/png_file.h"
#include "util/input_error.h"
#include "util/module_loader.h"

namespace nenrin {

namespace {

constexpr double kMaxValues = double(1u << 30);

/// R, G, B, A (or Y, A) first, then the rest by name: the order textures and maps expect.
std::vector<size_t> channelOrder(const std::vector<std::string>& names) {
    auto rank = [](const std::string& n) {
        static const std::vector<std::string> first = {"R", "G", "B", "A", "Y"};
        auto it = std::find(first.begin(), first.end(), n);
        return it == first.end() ? first.size() : size_t(it - first.begin());
    };
    const bool rgb = std::find(names.begin(), names.end(), "R") != names.end();
    std::vector<size_t> order(names.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        size_t ra = rank(names[a]), rb = rank(names[b]);
        if (!rgb) {  // grey: Y before A
            if (names[a] == "Y") ra = 0;
            if (names[b] == "Y") rb = 0;
        }
        if (ra != rb) return ra < rb;
        return names[a] < names[b];
    });
    return order;
}

ImageFile readExr(const std::string& path) {
    ImageFile image;
    try {
        Imf::InputFile file(path.c_str());
        const Imf::Header& header = file.header();
        const Imath::Box2i data = header.dataWindow();
        const double w = double(data.max.x) - data.min.x + 1,
                     h = double(data.max.y) - data.min.y + 1;
        std::vector<std::string> names;
        for (auto it = header.channels().begin(); it != header.channels().end(); ++it)
            names.push_back(it.name());
        if (!(w >= 1 && h >= 1) || w * h * std::max<size_t>(1, names.size()) > kMaxValues)
            throw InputError(path, "",
                             fmt::format("a {}x{} image of {} channels: expected at most 2^30 "
                                         "values",
                                         w, h, names.size()));
        image.width = static_cast<int>(w);
        image.height = static_cast<int>(h);
        const std::vector<size_t> order = channelOrder(names);
        for (size_t i : order) image.channelNames.push_back(names[i]);
        image.channels = static_cast<int>(names.size());
        image.floatingPoint = true;
        image.pixels.assign(size_t(image.width) * image.height * image.channels, 0.f);
        const size_t stride = names.size() * sizeof(float);
        char* base = reinterpret_cast<char*>(image.pixels.data()) -
                     (static_cast<ptrdiff_t>(data.min.y) * image.width + data.min.x) *
                         static_cast<ptrdiff_t>(stride);
        Imf::FrameBuffer frame;
        for (size_t c = 0; c < order.size(); ++c)
            frame.insert(names[order[c]], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), stride,
                                                     stride * image.width));
        file.setFrameBuffer(frame);
        file.readPixels(data.min.y, data.max.y);
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw InputError(path, "", std::string("cannot read the EXR (damaged?): ") + e.what());
    }
    return image;
}

/// A function of the OpenImageIO module; a module that cannot be loaded is an error of `path`.
void* oiioSymbol(const char* symbol, const std::string& feature, const std::string& path) {
    try {
        return moduleSymbol("libnenrin_oiio_reader.so", NENRIN_OIIO_MODULE, symbol, feature);
    } catch (const InputError& e) {
        throw InputError(path, "", e.what());
    }
}

ImageFile readThroughOiio(const std::string& path) {
    const std::string feature = "reading images other than EXR and PNG";
    auto read = reinterpret_cast<NenrinOiioReadFn>(oiioSymbol("nenrin_oiio_read", feature, path));
    auto release =
        reinterpret_cast<NenrinOiioFreeFn>(oiioSymbol("nenrin_oiio_free", feature, path));
    NenrinOiioImage raw{};
    char error[1024] = {};
    if (read(path.c_str(), &raw, error, sizeof error) != 0)
        throw InputError(path, "", std::string("cannot read the image: ") + error);
    ImageFile image;
    image.width = raw.width;
    image.height = raw.height;
    image.channels = raw.channels;
    image.floatingPoint = raw.floatingPoint != 0;
    image.pixels.assign(raw.pixels, raw.pixels + size_t(raw.width) * raw.height * raw.channels);
    release(&raw);
    std::string names = raw.names;
    for (size_t start = 0; image.channelNames.size() < size_t(image.channels);) {
        size_t comma = names.find(',', start);
        if (start >= names.size()) {
            image.channelNames.push_back(fmt::format("channel{}", image.channelNames.size()));
            continue;
        }
        image.channelNames.push_back(names.substr(start, comma - start));
        start = comma == std::string::npos ? names.size() : comma + 1;
    }
    return image;
}

}  // namespace

ImageFile readImageFile(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw InputError(path, "", "no such file");
    if (!std::filesystem::is_regular_file(path, ec))
        throw InputError(path, "", "not a regular file");
    char magic[8] = {};
    std::ifstream(path, std::ios::binary).read(magic, sizeof magic);
    if (magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 && magic[3] == 0x01)
        return readExr(path);
    if (std::string(magic, 8) == "\x89PNG\r\n\x1a\n") return readPng(path);
    return readThroughOiio(path);
}

ImageFile resizeImageFile(const ImageFile& image, int width, int height, const std::string& filter,
                          const std::string& path) {
    auto resize = reinterpret_cast<NenrinOiioResizeFn>(
        oiioSymbol("nenrin_oiio_resize", "resizing images", path));
    ImageFile out = image;
    out.width = width;
    out.height = height;
    out.pixels.assign(size_t(width) * height * image.channels, 0.f);
    char error[1024] = {};
    if (resize(image.pixels.data(), image.width, image.height, image.channels, filter.c_str(),
               width, height, out.pixels.data(), error, sizeof error) != 0)
        throw InputError(path, "", std::string("cannot resize the image: ") + error);
    return out;
}

}  // namespace nenrin
