#pragma once
/// PNG files through libpng: the 8-bit previews nenrin writes, and textures it reads.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "renderer/image_file.h"

namespace nenrin {

/// What the values of a PNG are: sRGB colour (marked with an sRGB chunk) or data (normals,
/// roughness: no colour chunk, so no tool converts them).
enum class PngValues { SrgbColour, Data };

/// Writes 8-bit RGB (3 per pixel, row 0 at the top) to `writePath`, with `text` as tEXt chunks;
/// errors name `finalPath`. Throws InputError if writing fails (disk full).
void writePng8(const std::string& finalPath, const std::string& writePath, int width, int height,
               const std::vector<uint8_t>& rgb, const std::map<std::string, std::string>& text,
               PngValues values = PngValues::SrgbColour);

/// Reads a PNG of any bit depth and colour type as float (values / 255 or / 65535, no
/// colour conversion): grey, grey + alpha, RGB or RGBA. Throws InputError naming `path`.
ImageFile readPng(const std::string& path);

}  // namespace nenrin
