#pragma once
/// Wood's own colour line: where wood is darker it is also more saturated (late wood against
/// early wood, a streak, a cell's shadow), so the anatomy's brightness changes can be taken
/// along that line instead of scaling every channel alike, which turns a pink or brown wood's
/// dark speckle grey (the grain's `anatomy.colour_line`, docs/grain-format.md). The line is
/// read from the grain's early and late wood; the luminance each change gives is the grey
/// one's, so every figure measured on lightness (fine and mid texture energy, ring contrast)
/// stays as it was.

#include "grain/rgb.h"
#include "shader/wood_anatomy.h"

namespace nenrin {

/// Per channel, how strongly the wood's colour changes with its brightness: ln(late / early
/// wood), over its luminance-weighted mean, each channel within 0.5-2 of it. {1, 1, 1} (grey)
/// where late and early wood hardly differ in luminance.
Rgb woodColourLine(const Rgb& earlyWood, const Rgb& lateWood);

/// `albedo` under the anatomy's brightness b taken along `line` (per channel 1 + (b - 1) s
/// line, s setting the luminance to b times the albedo's), then its pores' darkening, each
/// channel's factor at least 0. With a grey line exactly albedo x anatomy.filter().
Rgb alongColourLine(const Rgb& albedo, const AnatomySample& anatomy, const Rgb& line);

}  // namespace nenrin
