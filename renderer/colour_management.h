#pragma once
/// Display previews through OpenColorIO: scene-linear Rec.709 pixels -> 8-bit sRGB PNG.
/// Uses $OCIO when set, else the small config shipped in share/ocio/nenrin.ocio (compiled in).
/// The config is read afresh on every call, so a change of $OCIO takes effect at once.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace nenrin {

/// Name of the config in use: "nenrin built-in (share/ocio/nenrin.ocio)" or the $OCIO path.
std::string displayConfigName();

/// The text of share/ocio/nenrin.ocio as compiled into the library.
std::string_view builtinDisplayConfig();

/// Converts scene-linear RGB floats (3 per pixel, row 0 at the top) to 8-bit display values
/// through OCIO (scene_linear role -> display/view), with exposure in stops applied first.
/// With $OCIO set, its default display and view; otherwise display "sRGB", view "Standard".
/// NaN becomes 0 and display values are clamped to [0, 1] before rounding to nearest.
/// Throws InputError (file = the $OCIO path) when the $OCIO config cannot be loaded or has no
/// usable display, std::invalid_argument when rgb does not hold width x height x 3 values.
std::vector<uint8_t> toDisplay8(std::span<const float> rgb, int width, int height,
                                double exposureStops = 0);

/// Writes that as an 8-bit sRGB PNG (libpng), atomically (util/atomic_output.h:
/// AtomicOutput writes a temporary file and renames on commit). Throws InputError for a bad path
/// (not a writable .png name) or a bad $OCIO, std::invalid_argument for an image without pixels.
void writePreviewPng(const std::string& path, std::span<const float> rgb, int width, int height,
                     double exposureStops = 0);

}  // namespace nenrin
