#pragma once
/// Writing float images as EXR (OpenImageIO) the one way nenrin does it: zip compression,
/// linear, nenrin:KEY metadata and a fixed date so the same pixels give the same bytes.

#include <map>
#include <string>
#include <vector>

namespace nenrin {

/// Writes `pixels` (channel-interleaved, row 0 at the top) to `writePath`; errors name
/// `finalPath` (the name the caller will rename it to). A channel named "A" is the alpha.
void writeFloatExr(const std::string& finalPath, const std::string& writePath, int width,
                   int height, const std::vector<std::string>& channels, const float* pixels,
                   const std::map<std::string, std::string>& metadata);

}  // namespace nenrin
