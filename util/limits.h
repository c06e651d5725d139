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

/// The smallest values that make physical sense for the growth field's speeds, widths and
/// wavelengths. Smaller ones are typos or hostile input: they overflow growth times to
/// infinity (1e-308 once crashed the shader), so files are refused below them, naming these.
inline constexpr double kMinElongationSpeed = 1e-4;   ///< m/year: 0.1 mm a year
inline constexpr double kMinRadialSpeed = 1e-5;       ///< m/year: 0.01 mm a year
inline constexpr double kMinRingWidth = 1e-6;         ///< m: 1 um, finer than any measurement
inline constexpr double kMinBranchGamma = 1e-3;       ///< of the trunk's radial speed
inline constexpr double kMinBranchLength = 1e-3;      ///< m
inline constexpr double kMinDeathTime = 0.01;         ///< years
inline constexpr double kMinSwayWavelength = 0.01;    ///< m: sway bends rings over centimetres+
inline constexpr double kMinWanderWavelength = 1e-3;  ///< m: rings wander over millimetres+
inline constexpr double kMinWarpStep = 1e-4;          ///< m: a warp lattice's step (grain "warp")
inline constexpr double kMaxWarp = 0.05;              ///< m: its largest displacement
inline constexpr double kMinCellSize = 1e-6;          ///< m: of the micro-structure's cells

/// True if a width x height image is within kMaxImageSide and kMaxImagePixels.
constexpr bool imageSizeAllowed(long long width, long long height) {
    return width >= 1 && height >= 1 && width <= kMaxImageSide && height <= kMaxImageSide &&
           width * height <= kMaxImagePixels;
}

}  // namespace nenrin
