#pragma once
/// Cross-dating the faces (dendrochronology's word: matching ring patterns between samples).
/// A ring is one shell around the pith, so every face it crosses shows the same year's colour
/// at the same distance from the pith: with the pith in the right place, the faces' lightness
/// averaged over thin shells (each face on its own) rises and falls together wherever their
/// radii overlap. Faces parallel to the pith show every ring as a line along it wherever the
/// pith lies, so their ring directions cannot place it (docs/fit.md, "Why H11's B fails"); the
/// agreement of their ring patterns can.

#include <span>

#include "fit/face_photo.h"
#include "fit/pith_fit.h"

namespace nenrin {

/// The line moved across itself (its direction kept) to where the faces' ring patterns agree
/// best. Agreement: the mean correlation, over pairs of faces, of their shell means of L* (less
/// its 6 px blur: the rings, not the stains), 0.2 mm shells, weighed by the shells the two
/// share (at least 25). The search: a polar grid around the sample (2 mm to 2 m out), then finer
/// grids around the best few, on `threads` workers (0: all cores; the answer is the same on any
/// number). Places the ring directions fit over 2 degrees worse than the line does are not taken,
/// nor places inside the sample when the line is outside it. The line as it was if no place agrees
/// better than it by `margin`.
PithLine crossDatePithLine(const PithLine& pith, std::span<const FacePhoto> faces, int threads,
                           double margin = 0.03);

}  // namespace nenrin
