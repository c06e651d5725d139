#pragma once
/// The caps on what a command may be asked to make or read, in one place. Beyond them a
/// request is almost surely a typo (an extra zero) that would take hours or all memory; each
/// is checked where the value is read, with a message naming the file or option.

namespace nenrin {

/// Pixels per side of any image nenrin makes: a render, a slice bake, a UV texture set.
inline constexpr int kMaxImageSide = 16384;
/// Pixels of any such image (64 M: a 8192 x 8192 frame).
inline constexpr long long kMaxImagePixels = 1LL << 26;
/// Samples along the longest edge of a volume bake.
inline constexpr int kMaxVolumeSide = 512;
/// Samples per pixel of a render.
inline constexpr int kMaxSpp = 1 << 16;
/// Where nenrin works in tree or scene space (m): no tree and no product is 10 km away.
inline constexpr double kMaxCoordinate = 1e4;

/// True if a width x height image is within kMaxImageSide and kMaxImagePixels.
constexpr bool imageSizeAllowed(long long width, long long height) {
    return width >= 1 && height >= 1 && width <= kMaxImageSide && height <= kMaxImageSide &&
           width * height <= kMaxImagePixels;
}

}  // namespace nenrin
