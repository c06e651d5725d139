#pragma once
/// Writers for baked grids. Each writes to temporary files and renames them only when all were
/// written, so a failed bake leaves no partial output.
///  - EXR (OpenImageIO): channels R, G, B, A, T, knot as 32-bit float; a volume is stored as an
///    atlas of its z slices stacked top to bottom (height = Sy x Sz) with its layout in the
///    metadata (nenrin:volume_resolution, nenrin:box).
///  - OpenVDB: one float grid per channel, index-to-world transform from the bake box.
///  - POV-Ray df3: one 16-bit file per colour channel plus knot (NAME.R.df3, ...), and NAME.inc
///    with the pigment that reassembles them (see docs/bake.md).

#include <string>
#include <vector>

#include "renderer/bake/baked_grid.h"
#include "util/atomic_output.h"  // checkOutputName

namespace nenrin {

/// Writes a 2D grid (depth 1) or a volume atlas as EXR; a band of a grid (a split job's part)
/// as that band of the image's rows. Returns the files written. OpenVDB and df3 need the
/// whole grid.
std::vector<std::string> writeExr(const BakedGrid& grid, const std::string& path);
std::vector<std::string> writeVdb(const BakedGrid& grid, const std::string& path);
std::vector<std::string> writeDf3(const BakedGrid& grid, const std::string& path);

/// An 8-bit sRGB preview of a slice's colour over its coverage (black outside the felled log),
/// through OpenColorIO.
void writeSlicePreviewPng(const BakedGrid& grid, const std::string& path);

/// Dispatches on the extension (.exr, .vdb, .df3); throws InputError for anything else.
std::vector<std::string> writeVolume(const BakedGrid& grid, const std::string& path);

}  // namespace nenrin
