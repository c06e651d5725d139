#include "renderer/environment_map.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "renderer/image_file.h"
#include "util/input_error.h"

namespace nenrin {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInv4Pi = 1 / (4 * kPi);
// Lat-long images larger than this are surely a mistake (16k x 16k is 3 GB of float RGB).
constexpr long long kMaxTexels = 1LL << 28;

/// Cumulative table of n weights into cdf[0..n]: cdf[0] = 0, cdf[n] = 1, and cdf[k+1] - cdf[k]
/// (as stored) is the probability of k. Every positive weight keeps a non-zero step even when
/// it is below the precision of T; all-zero weights give a uniform table.
template <typename T>
void buildCdf(const double* w, int n, T* cdf) {
    double total = 0;
    int last = -1;
    for (int k = 0; k < n; ++k) {
        total += w[k];
        if (w[k] > 0) last = k;
    }
    cdf[0] = 0;
    cdf[n] = 1;
    if (last < 0) {
        for (int k = 1; k < n; ++k) cdf[k] = static_cast<T>(static_cast<double>(k) / n);
        return;
    }
    const T below1 = std::nextafter(T(1), T(0));
    double running = 0;
    for (int k = 0; k < n - 1; ++k) {
        running += w[k];
        T c = k >= last ? T(1) : std::min(static_cast<T>(running / total), below1);
        if (w[k] > 0 && c <= cdf[k]) c = std::min(std::nextafter(cdf[k], T(2)), T(1));
        cdf[k + 1] = std::max(c, cdf[k]);
    }
}

/// The k with cdf[k] <= x < cdf[k+1] (zero-probability entries are never chosen) and the
/// position of x within that step, in [0, 1].
template <typename T>
int invertCdf(const T* cdf, int n, double x, double& fraction) {
    int k = static_cast<int>(std::upper_bound(cdf, cdf + n + 1, x) - cdf) - 1;
    k = std::clamp(k, 0, n - 1);
    double lo = cdf[k], hi = cdf[k + 1];
    fraction = hi > lo ? std::clamp((x - lo) / (hi - lo), 0.0, 1.0) : 0.5;
    return k;
}

/// Integrals over [p, q] of sin(pi v) and of (v - c) sin(pi v).
double integralSin(double p, double q) { return (std::cos(kPi * p) - std::cos(kPi * q)) / kPi; }
double integralLinearSin(double p, double q, double c) {
    auto f = [](double v) {
        return -v * std::cos(kPi * v) / kPi + std::sin(kPi * v) / (kPi * kPi);
    };
    return f(q) - f(p) - c * integralSin(p, q);
}

/// How row j's solid angle integral of a bilinear reconstruction depends on the values at the
/// centres of rows j-1, j and j+1 (in v the reconstruction is linear between row centres and
/// constant in the outer half rows): the integral over row j of s(v) sin(pi v) dv is
/// below * s[j-1] + own * s[j] + above * s[j+1].
struct RowCoefficients {
    double below = 0, own = 0, above = 0;
};

RowCoefficients rowCoefficients(int j, int height) {
    const double h = 1.0 / height;
    const double top = j * h, centre = (j + 0.5) * h, bottom = (j + 1) * h;
    RowCoefficients c;
    if (j == 0) {
        c.own += integralSin(top, centre);
    } else {  // linear from row j-1's centre (t = 0) to row j's (t = 1)
        double t = integralLinearSin(top, centre, centre - h) * height;
        c.below += integralSin(top, centre) - t;
        c.own += t;
    }
    if (j == height - 1) {
        c.own += integralSin(centre, bottom);
    } else {
        double t = integralLinearSin(centre, bottom, centre) * height;
        c.own += integralSin(centre, bottom) - t;
        c.above += t;
    }
    return c;
}

}  // namespace

EnvironmentMap EnvironmentMap::constant(const Rgb& radiance) {
    EnvironmentMap m;
    m.constant_ = radiance;
    m.average_ = radiance;
    return m;
}

EnvironmentMap EnvironmentMap::load(const std::string& path, double scale, double rotation) {
    if (!std::isfinite(scale) || scale < 0)
        throw InputError(
            path, "", fmt::format("the environment scale must be finite and >= 0, got {}", scale));
    if (!std::isfinite(rotation))
        throw InputError(path, "", "the environment rotation must be a finite angle");
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        throw InputError(path, "", "cannot read environment map: no such file");
    if (!std::filesystem::is_regular_file(path, ec))
        throw InputError(path, "", "cannot read environment map: not a regular file");

    const ImageFile image = readImageFile(path);
    const int width = image.width, height = image.height, channels = image.channels;
    const bool grey = channels == 1;  // else R, G, B come first (image_file.h)
    if (channels == 2 || channels < 1)
        throw InputError(path, "",
                         fmt::format("an environment map needs 3 channels (R, G, B) or 1 (grey), "
                                     "found {}",
                                     channels));
    if (width < 2 || height < 1)
        throw InputError(path, "",
                         fmt::format("an environment map must be a 2D image of at least 2 x 1 "
                                     "pixels, found {} x {}",
                                     width, height));
    if (static_cast<long long>(width) * height > kMaxTexels)
        throw InputError(path, "",
                         fmt::format("environment map of {} x {} pixels is too large (at most "
                                     "{} pixels)",
                                     width, height, kMaxTexels));
    EnvironmentMap m;
    m.width_ = width;
    m.height_ = height;
    m.rotationU_ = rotation / (2 * kPi);
    m.rotationU_ -= std::floor(m.rotationU_);
    const size_t count = static_cast<size_t>(width) * height;
    m.texels_.resize(count * 3);
    std::vector<float> greyPixels(grey ? count : 0);
    for (size_t p = 0; p < count; ++p) {
        const float* px = &image.pixels[p * channels];
        if (grey)
            greyPixels[p] = px[0];
        else
            for (int c = 0; c < 3; ++c) m.texels_[p * 3 + c] = px[c];
    }
    static constexpr const char* kNames[3] = {"R", "G", "B"};
    for (size_t p = 0; p < count; ++p)
        for (int c = 0; c < 3; ++c) {
            float& texel = m.texels_[p * 3 + c];
            float value = grey ? greyPixels[p] : texel;
            auto where = [&] { return fmt::format("pixel ({}, {})", p % width, p / width); };
            const char* channel = grey ? "grey" : kNames[c];
            if (!std::isfinite(value))
                throw InputError(path, where(), fmt::format("channel {} is {}", channel, value));
            if (value < 0)
                throw InputError(path, where(),
                                 fmt::format("channel {} is negative ({}): radiance must be >= 0",
                                             channel, value));
            texel = static_cast<float>(value * scale);
            if (!std::isfinite(texel))
                throw InputError(
                    path, where(),
                    fmt::format("channel {} times the scale {} overflows", channel, scale));
        }
    m.buildDistribution();
    return m;
}

void EnvironmentMap::buildDistribution() {
    const int W = width_, H = height_;
    cosRowEdge_.resize(H + 1);
    texelSolidAngle_.resize(H);
    for (int j = 0; j <= H; ++j) cosRowEdge_[j] = std::cos(kPi * j / H);
    cosRowEdge_[0] = 1;
    cosRowEdge_[H] = -1;
    for (int j = 0; j < H; ++j)  // cos a - cos b without cancellation near the poles
        texelSolidAngle_[j] =
            2 * kPi / W * 2 * std::sin(kPi * (j + 0.5) / H) * std::sin(kPi / (2 * H));

    // The integral of a bilinear reconstruction over one texel's u extent: 1/8, 3/4, 1/8 of the
    // texels left, at and right of it (wrapping), times the texel width (dropped: a constant).
    auto filteredLuminance = [&](int j, std::vector<double>& out) {
        std::vector<double> lum(W);
        for (int i = 0; i < W; ++i) {
            lum[i] = luminance(texel(i, j));
        }
        for (int i = 0; i < W; ++i)
            out[i] = (lum[(i + W - 1) % W] + 6 * lum[i] + lum[(i + 1) % W]) / 8;
    };

    // Texel weights: the integral of luminance(radiance()) over the texel's solid angle (up to
    // a constant), from the filtered rows j-1, j, j+1. Kept three rows at a time.
    std::vector<double> rowWeight(H), weights(W), previous(W), current(W), next(W);
    columnCdf_.resize(static_cast<size_t>(W + 1) * H);
    Rgb integral;  // of radiance() sin(theta) dv, from each row's mean and its coefficients
    filteredLuminance(0, current);
    for (int j = 0; j < H; ++j) {
        if (j + 1 < H) filteredLuminance(j + 1, next);
        RowCoefficients c = rowCoefficients(j, H);
        double sum = 0;
        for (int i = 0; i < W; ++i) {
            weights[i] = c.own * current[i];
            if (j > 0) weights[i] += c.below * previous[i];
            if (j + 1 < H) weights[i] += c.above * next[i];
            sum += weights[i];
        }
        rowWeight[j] = sum;
        buildCdf(weights.data(), W, &columnCdf_[static_cast<size_t>(W + 1) * j]);

        // Row k's mean enters the integral through rows k-1, k and k+1.
        double share = c.own + (j > 0 ? rowCoefficients(j - 1, H).above : 0) +
                       (j + 1 < H ? rowCoefficients(j + 1, H).below : 0);
        Rgb mean;
        for (int i = 0; i < W; ++i) mean = mean + texel(i, j);
        integral = integral + mean * (share / W);

        std::swap(previous, current);
        std::swap(current, next);
    }
    // Over the sphere d(omega) = 2 pi^2 sin(pi v) du dv; the mean divides by 4 pi.
    average_ = integral * (kPi / 2);

    double total = 0;
    for (double w : rowWeight) total += w;
    if (!(total > 0)) {  // black: sample uniformly over the sphere
        for (int j = 0; j < H; ++j) {
            rowWeight[j] = texelSolidAngle_[j];
            std::fill(weights.begin(), weights.end(), 1.0);
            buildCdf(weights.data(), W, &columnCdf_[static_cast<size_t>(W + 1) * j]);
        }
    }
    rowCdf_.resize(H + 1);
    buildCdf(rowWeight.data(), H, rowCdf_.data());
}

Rgb EnvironmentMap::texel(int i, int j) const {
    const float* t = &texels_[(static_cast<size_t>(j) * width_ + i) * 3];
    return {t[0], t[1], t[2]};
}

EnvironmentMap::Location EnvironmentMap::locate(const Vec3& d) const {
    double u = 0.5 + std::atan2(d.x, -d.z) / (2 * kPi) + rotationU_;
    u -= std::floor(u);
    if (!(u >= 0 && u < 1)) u = 0;  // u rounded up to 1, or a non-finite direction
    double v = std::acos(std::clamp(d.y, -1.0, 1.0)) / kPi;
    if (!(v >= 0 && v <= 1)) v = 0;
    int i = std::min(static_cast<int>(u * width_), width_ - 1);
    int j = std::min(static_cast<int>(v * height_), height_ - 1);
    return {u, v, i, j};
}

Rgb EnvironmentMap::bilinear(double u, double v) const {
    double x = u * width_ - 0.5, y = v * height_ - 0.5;
    double fx = std::floor(x), fy = std::floor(y);
    double tx = x - fx, ty = y - fy;
    int i0 = static_cast<int>(fx), j0 = static_cast<int>(fy);
    int i1 = (i0 + 1) % width_, j1 = std::min(j0 + 1, height_ - 1);
    i0 = (i0 + width_) % width_;  // wraps around in u, clamps in v
    j0 = std::max(j0, 0);
    return mix(mix(texel(i0, j0), texel(i1, j0), tx), mix(texel(i0, j1), texel(i1, j1), tx), ty);
}

double EnvironmentMap::texelPdf(int i, int j) const {
    const float* c = &columnCdf_[static_cast<size_t>(width_ + 1) * j];
    double row = rowCdf_[j + 1] - rowCdf_[j];
    double column = static_cast<double>(c[i + 1]) - static_cast<double>(c[i]);
    return row * column / texelSolidAngle_[j];
}

Vec3 EnvironmentMap::directionAt(double u, double cosTheta) const {
    double phi = 2 * kPi * (u - rotationU_ - 0.5);
    double sinTheta = std::sqrt(std::max(0.0, (1 - cosTheta) * (1 + cosTheta)));
    return {sinTheta * std::sin(phi), cosTheta, -sinTheta * std::cos(phi)};
}

Rgb EnvironmentMap::radiance(const Vec3& direction) const {
    if (isConstant()) return constant_;
    Location at = locate(direction);
    return bilinear(at.u, at.v);
}

double EnvironmentMap::pdf(const Vec3& direction) const {
    if (isConstant()) return kInv4Pi;
    Location at = locate(direction);
    return texelPdf(at.i, at.j);
}

EnvironmentMap::Sample EnvironmentMap::sample(double u1, double u2) const {
    const double below1 = std::nextafter(1.0, 0.0);
    u1 = std::clamp(u1, 0.0, below1);
    u2 = std::clamp(u2, 0.0, below1);
    if (isConstant()) {
        double cosTheta = 1 - 2 * u1, phi = 2 * kPi * u2;
        double sinTheta = std::sqrt(std::max(0.0, (1 - cosTheta) * (1 + cosTheta)));
        return {
            {sinTheta * std::sin(phi), cosTheta, -sinTheta * std::cos(phi)}, constant_, kInv4Pi};
    }
    double fv, fu;
    int j = invertCdf(rowCdf_.data(), height_, u1, fv);
    int i = invertCdf(&columnCdf_[static_cast<size_t>(width_ + 1) * j], width_, u2, fu);
    // Uniform in solid angle within the texel: uniform in phi and in cos(theta).
    double top = cosRowEdge_[j], bottom = cosRowEdge_[j + 1];
    Vec3 d = directionAt((i + fu) / width_, top - fv * (top - bottom));
    Location at = locate(d);
    if (at.i != i || at.j != j) {
        // Rounding put the direction on a neighbour's edge (probability ~1e-15): the texel
        // centre keeps pdf() and the texel's probability in agreement.
        d = directionAt((i + 0.5) / width_, 0.5 * (top + bottom));
        at = locate(d);
    }
    return {d, bilinear(at.u, at.v), texelPdf(i, j)};
}

}  // namespace nenrin
