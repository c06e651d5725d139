#pragma once
/// Float images as EXR (OpenEXR) the one way nenrin writes them: 32-bit float channels, zip
/// compression, linear, nenrin:KEY metadata and nothing that changes from run to run, so the
/// same pixels give the same bytes.

#include <map>
#include <string>
#include <vector>

#include "renderer/row_band.h"

namespace nenrin {

/// What an EXR's values are: scene-linear colour (marked oiio:ColorSpace "Linear"), or data
/// such as normals and roughness (marked colorInteropID "data", the ASWF Color Interop
/// Forum's tag, so no colour-managed tool converts them).
enum class ExrValues { SceneLinear, Data };

/// Writes `pixels` (channel-interleaved, row 0 at the top) to `writePath`; errors name
/// `finalPath` (the name the caller will rename it to). A channel named "A" is the alpha.
/// With a band, `pixels` hold only its rows, written as the EXR data window of a width x
/// height frame (the display window): how the parts of a split job are stored. `threads` > 1
/// compresses that many blocks of rows at once (the file's bytes do not depend on it).
void writeFloatExr(const std::string& finalPath, const std::string& writePath, int width,
                   int height, const std::vector<std::string>& channels, const float* pixels,
                   const std::map<std::string, std::string>& metadata, RowBand band = {},
                   ExrValues values = ExrValues::SceneLinear, int threads = 1);

/// One channel of an image in memory: sample i (row-major, the band's rows only) at
/// values[i * stride].
struct ExrChannel {
    std::string name;
    const float* values;
    size_t stride = 1;
};

/// writeFloatExr for channels that lie apart in memory (a film's planes): written from where
/// they are, without an interleaved copy. The channels are checked for non-finite values one
/// after the other.
void writeFloatExrChannels(const std::string& finalPath, const std::string& writePath, int width,
                           int height, const std::vector<ExrChannel>& channels,
                           const std::map<std::string, std::string>& metadata, RowBand band = {},
                           ExrValues values = ExrValues::SceneLinear, int threads = 1);

/// An EXR read back whole: its data window, channels, pixels and nenrin:KEY metadata.
struct FloatExr {
    int width = 0, height = 0;  ///< the display window (the frame); its origin must be 0, 0
    RowBand band;               ///< the data window's rows (its columns must span the frame)
    std::vector<std::string> channels;
    std::vector<float> pixels;                    ///< channel-interleaved, the band's rows only
    std::map<std::string, std::string> metadata;  ///< nenrin:KEY attributes, without "nenrin:"
};

/// Reads an EXR written by writeFloatExr; throws InputError naming `path` if it cannot be read
/// or is not such a file (a tiled or deep file, a window that is not a band of rows).
FloatExr readFloatExr(const std::string& path);

/// Puts the channels of `exr` in `order` (OpenEXR stores them sorted by name, and readers
/// may list them in another order than they were written); throws InputError naming `path`
/// unless the file has exactly these channels.
void orderChannels(FloatExr& exr, const std::vector<std::string>& order, const std::string& path);

}  // namespace nenrin
