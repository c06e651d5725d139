#pragma once
/// Scene-linear RGB (Rec.709 primaries).

namespace nenrin {

struct Rgb {
    double r = 0, g = 0, b = 0;
    constexpr Rgb operator+(const Rgb& o) const { return {r + o.r, g + o.g, b + o.b}; }
    constexpr Rgb operator-(const Rgb& o) const { return {r - o.r, g - o.g, b - o.b}; }
    constexpr Rgb operator*(double s) const { return {r * s, g * s, b * s}; }
    constexpr bool operator==(const Rgb&) const = default;
};

constexpr Rgb mix(const Rgb& a, const Rgb& b, double t) { return a + (b - a) * t; }

/// Component-wise product (a filter applied to a colour).
constexpr Rgb multiply(const Rgb& a, const Rgb& b) { return {a.r * b.r, a.g * b.g, a.b * b.b}; }

/// True if no channel is positive: nothing to add or carry on.
constexpr bool isBlack(const Rgb& c) { return c.r <= 0 && c.g <= 0 && c.b <= 0; }

/// Luminance Y of the Rec.709 primaries.
constexpr double luminance(const Rgb& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

}  // namespace nenrin
