#include "renderer/image_error/flip.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace nenrin {

namespace {

/// One channel, row-major.
using Channel = std::vector<double>;

// --- Colour spaces (D65), as the FLIP papers define them ---------------------------------

constexpr double kWhite[3] = {0.950428545, 1.0, 1.088900371};

double linearFromSrgb(double v) {
    return v > 0.04045 ? std::pow((v + 0.055) / 1.055, 2.4) : v / 12.92;
}
double srgbFromLinear(double v) {
    return v > 0.0031308 ? 1.055 * std::pow(v, 1 / 2.4) - 0.055 : 12.92 * v;
}

void xyzFromLinear(const double rgb[3], double xyz[3]) {
    xyz[0] = (10135552 * rgb[0] + 8788810 * rgb[1] + 4435075 * rgb[2]) / 24577794.0;
    xyz[1] = (2613072 * rgb[0] + 8788810 * rgb[1] + 887015 * rgb[2]) / 12288897.0;
    xyz[2] = (1425312 * rgb[0] + 8788810 * rgb[1] + 70074185 * rgb[2]) / 73733382.0;
}
void linearFromXyz(const double xyz[3], double rgb[3]) {
    rgb[0] = 3.241003275 * xyz[0] - 1.537398934 * xyz[1] - 0.498615861 * xyz[2];
    rgb[1] = -0.969224334 * xyz[0] + 1.875930071 * xyz[1] + 0.041554224 * xyz[2];
    rgb[2] = 0.055639423 * xyz[0] - 0.204011202 * xyz[1] + 1.057148933 * xyz[2];
}

/// YCxCz: CIELAB without its cube root, linear in XYZ, so the eye's filters apply in it.
void ycxczFromXyz(const double xyz[3], double o[3]) {
    const double x = xyz[0] / kWhite[0], y = xyz[1] / kWhite[1], z = xyz[2] / kWhite[2];
    o[0] = 116 * y - 16;
    o[1] = 500 * (x - y);
    o[2] = 200 * (y - z);
}
void xyzFromYcxcz(const double o[3], double xyz[3]) {
    const double y = (o[0] + 16) / 116;
    xyz[0] = (y + o[1] / 500) * kWhite[0];
    xyz[1] = y * kWhite[1];
    xyz[2] = (y - o[2] / 200) * kWhite[2];
}

/// CIELAB with the Hunt adjustment (chroma scaled by 0.01 L: colours darken together).
void huntLabFromLinear(const double rgb[3], double lab[3]) {
    double xyz[3];
    xyzFromLinear(rgb, xyz);
    constexpr double d = 6.0 / 29;
    double f[3];
    for (int c = 0; c < 3; ++c) {
        const double t = xyz[c] / kWhite[c];
        f[c] = t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29;
    }
    lab[0] = 116 * f[1] - 16;
    lab[1] = 0.01 * lab[0] * 500 * (f[0] - f[1]);
    lab[2] = 0.01 * lab[0] * 200 * (f[1] - f[2]);
}

double hyab(const double a[3], const double b[3]) {
    return std::abs(a[0] - b[0]) + std::hypot(a[1] - b[1], a[2] - b[2]);
}

// --- Filters -------------------------------------------------------------------------------

/// Correlates along rows with `kx` and along columns with `ky` (odd lengths, centred), the
/// border sample repeated.
Channel separable(const Channel& in, int w, int h, const std::vector<double>& kx,
                  const std::vector<double>& ky) {
    const int rx = int(kx.size()) / 2, ry = int(ky.size()) / 2;
    Channel rows(in.size()), out(in.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double s = 0;
            for (int i = -rx; i <= rx; ++i)
                s += kx[i + rx] * in[size_t(y) * w + std::clamp(x + i, 0, w - 1)];
            rows[size_t(y) * w + x] = s;
        }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double s = 0;
            for (int i = -ry; i <= ry; ++i)
                s += ky[i + ry] * rows[size_t(std::clamp(y + i, 0, h - 1)) * w + x];
            out[size_t(y) * w + x] = s;
        }
    return out;
}

/// The contrast sensitivity of one opponent channel: a sum of (at most two) Gaussians in
/// degrees, a1 sqrt(pi / b1) exp(-pi^2 r^2 / b1) + ..., sampled over the radius of the widest
/// one, normalised to sum 1. Each Gaussian is separable, so the filter is their weighted sum.
struct Csf {
    double a[2], b[2];
};
constexpr Csf kAchromatic{{1, 0}, {0.0047, 1e-5}};
constexpr Csf kRedGreen{{1, 0}, {0.0053, 1e-5}};
constexpr Csf kBlueYellow{{34.1, 13.5}, {0.04, 0.025}};

Channel csfFilter(const Channel& in, int w, int h, const Csf& csf, double ppd) {
    const int r =
        int(std::ceil(3 * std::sqrt(0.04 / (2 * std::numbers::pi * std::numbers::pi)) * ppd));
    std::vector<double> g[2];
    double weight[2], total = 0;
    for (int k = 0; k < 2; ++k) {
        double sum = 0;
        for (int i = -r; i <= r; ++i) {
            const double x = i / ppd;
            g[k].push_back(std::exp(-std::numbers::pi * std::numbers::pi * x * x / csf.b[k]));
            sum += g[k].back();
        }
        weight[k] = csf.a[k] * std::sqrt(std::numbers::pi / csf.b[k]);
        total += weight[k] * sum * sum;
    }
    Channel out(in.size(), 0.0);
    for (int k = 0; k < 2; ++k) {
        if (csf.a[k] == 0) continue;
        const Channel part = separable(in, w, h, g[k], g[k]);
        for (size_t i = 0; i < out.size(); ++i) out[i] += weight[k] / total * part[i];
    }
    return out;
}

/// Edge (first derivative) or point (second derivative) detector of a Gaussian whose peak to
/// trough spans 0.082 degrees, its positive weights summing to 1 and negative ones to -1: the
/// derivative along x (`along`) and the Gaussian across (`across`).
void featureKernels(double ppd, bool edge, std::vector<double>& along,
                    std::vector<double>& across) {
    const double sd = 0.5 * 0.082 * ppd;
    const int r = int(std::ceil(3 * sd));
    along.clear();
    across.clear();
    double gsum = 0;
    for (int i = -r; i <= r; ++i) {
        const double g = std::exp(-double(i) * i / (2 * sd * sd));
        across.push_back(g);
        gsum += g;
        along.push_back(edge ? -i * g : (double(i) * i / (sd * sd) - 1) * g);
    }
    double positive = 0, negative = 0;
    for (double v : along) (v > 0 ? positive : negative) += std::abs(v);
    for (double& v : along) v /= (v > 0 ? positive : negative) * gsum;
}

/// The length of the feature response (x and y derivative) per pixel.
Channel featureStrength(const Channel& y, int w, int h, double ppd, bool edge) {
    std::vector<double> along, across;
    featureKernels(ppd, edge, along, across);
    const Channel fx = separable(y, w, h, along, across);
    const Channel fy = separable(y, w, h, across, along);
    Channel out(y.size());
    for (size_t i = 0; i < y.size(); ++i) out[i] = std::hypot(fx[i], fy[i]);
    return out;
}

/// The opponent channels of an sRGB image, and its filtered colours as Hunt-adjusted CIELAB.
struct Prepared {
    Channel y;                ///< normalised achromatic channel, (Y + 16) / 116
    std::vector<double> lab;  ///< 3 per pixel
};

Prepared prepare(const FlipImage& image, double ppd) {
    const int w = image.width, h = image.height;
    const size_t n = size_t(w) * h;
    Channel o[3];
    for (auto& c : o) c.resize(n);
    for (size_t i = 0; i < n; ++i) {
        double rgb[3], xyz[3], v[3];
        for (int c = 0; c < 3; ++c)
            rgb[c] = linearFromSrgb(std::clamp(double(image.rgb[3 * i + c]), 0.0, 1.0));
        xyzFromLinear(rgb, xyz);
        ycxczFromXyz(xyz, v);
        for (int c = 0; c < 3; ++c) o[c][i] = v[c];
    }
    Prepared p;
    p.y.resize(n);
    for (size_t i = 0; i < n; ++i) p.y[i] = (o[0][i] + 16) / 116;
    const Channel f[3] = {csfFilter(o[0], w, h, kAchromatic, ppd),
                          csfFilter(o[1], w, h, kRedGreen, ppd),
                          csfFilter(o[2], w, h, kBlueYellow, ppd)};
    p.lab.resize(3 * n);
    for (size_t i = 0; i < n; ++i) {
        double v[3] = {f[0][i], f[1][i], f[2][i]}, xyz[3], rgb[3];
        xyzFromYcxcz(v, xyz);
        linearFromXyz(xyz, rgb);
        for (double& c : rgb) c = std::clamp(c, 0.0, 1.0);  // back into the RGB cube
        huntLabFromLinear(rgb, &p.lab[3 * i]);
    }
    return p;
}

void checkSizes(const FlipImage& a, const FlipImage& b) {
    if (a.width != b.width || a.height != b.height || a.width <= 0 || a.height <= 0 ||
        a.rgb.size() != size_t(a.width) * a.height * 3 || b.rgb.size() != a.rgb.size())
        throw std::invalid_argument("FLIP: the images must be of one size, 3 floats per pixel");
}

/// ACES filmic (Narkowicz's fit, with the 0.6 pre-exposure folded in): y = (k0 x^2 + k1 x) /
/// (k3 x^2 + k4 x + k5).
constexpr double kAces[6] = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};

double aces(double x) {
    if (std::isinf(x)) return 1;
    const double y =
        (kAces[0] * x * x + kAces[1] * x + kAces[2]) / (kAces[3] * x * x + kAces[4] * x + kAces[5]);
    return std::clamp(y, 0.0, 1.0);
}

/// The value the tone curve maps to `t`.
double acesInverse(double t) {
    const double c0 = (kAces[1] - kAces[4] * t) / (kAces[0] - kAces[3] * t);
    const double c1 = (kAces[2] - kAces[5] * t) / (kAces[0] - kAces[3] * t);
    return -0.5 * c0 + std::sqrt(0.25 * c0 * c0 - c1);
}

FlipImage toneMapped(const FlipImage& image, double exposure) {
    FlipImage out = image;
    const double scale = std::exp2(exposure);
    for (float& v : out.rgb) v = float(srgbFromLinear(aces(scale * std::max(0.0f, v))));
    return out;
}

}  // namespace

std::vector<float> ldrFlip(const FlipImage& reference, const FlipImage& test, double ppd) {
    checkSizes(reference, test);
    if (!(ppd > 0) || !std::isfinite(ppd))
        throw std::invalid_argument("FLIP: pixels per degree must be a positive number");
    const int w = reference.width, h = reference.height;
    const Prepared r = prepare(reference, ppd), t = prepare(test, ppd);
    // The largest distance there is: Hunt-adjusted green to blue.
    constexpr double qc = 0.7, qf = 0.5, pc = 0.4, pt = 0.95;
    double green[3], blue[3];
    const double g[3] = {0, 1, 0}, b[3] = {0, 0, 1};
    huntLabFromLinear(g, green);
    huntLabFromLinear(b, blue);
    const double cmax = std::pow(hyab(green, blue), qc);
    const Channel edgesR = featureStrength(r.y, w, h, ppd, true),
                  edgesT = featureStrength(t.y, w, h, ppd, true),
                  pointsR = featureStrength(r.y, w, h, ppd, false),
                  pointsT = featureStrength(t.y, w, h, ppd, false);
    std::vector<float> error(size_t(w) * h);
    for (size_t i = 0; i < error.size(); ++i) {
        // Colour: the distance compressed, then spread so that small differences fill 0..0.95.
        const double d = std::pow(hyab(&r.lab[3 * i], &t.lab[3 * i]), qc);
        const double colour = d < pc * cmax ? pt / (pc * cmax) * d
                                            : pt + (d - pc * cmax) / (cmax - pc * cmax) * (1 - pt);
        // Features: a changed edge or point raises the colour error towards 1.
        const double feature =
            std::pow(std::max(std::abs(edgesR[i] - edgesT[i]), std::abs(pointsR[i] - pointsT[i])) /
                         std::numbers::sqrt2,
                     qf);
        error[i] = float(std::pow(colour, 1 - feature));
    }
    return error;
}

FlipExposures flipExposures(const FlipImage& reference) {
    std::vector<double> luminance;
    luminance.reserve(reference.rgb.size() / 3);
    for (size_t i = 0; i + 2 < reference.rgb.size(); i += 3)
        luminance.push_back(std::max(0.0, 0.2126 * reference.rgb[i] +
                                              0.7152 * reference.rgb[i + 1] +
                                              0.0722 * reference.rgb[i + 2]));
    FlipExposures e;
    if (luminance.empty()) return e;
    const double high = *std::max_element(luminance.begin(), luminance.end());
    if (!(high > 0)) return e;
    // The median; where over half the image is black (a product on black), the median of
    // the lit pixels, so the exposures end.
    auto median = [](std::vector<double> v) {
        const size_t m = v.size() / 2;
        std::nth_element(v.begin(), v.begin() + m, v.end());
        double mid = v[m];
        if (v.size() % 2 == 0) mid = 0.5 * (mid + *std::max_element(v.begin(), v.begin() + m));
        return mid;
    };
    double low = median(luminance);
    if (!(low > 0)) {
        std::vector<double> lit;
        for (double y : luminance)
            if (y > 0) lit.push_back(y);
        low = median(lit);
    }
    const double x = acesInverse(0.85);
    e.start = std::log2(x / high);
    e.stop = std::log2(x / low);
    e.count = std::max(2, int(std::ceil(e.stop - e.start)));
    return e;
}

std::vector<float> hdrFlip(const FlipImage& reference, const FlipImage& test,
                           const FlipExposures& exposures, double ppd) {
    checkSizes(reference, test);
    if (exposures.count < 1 || !std::isfinite(exposures.start) || !std::isfinite(exposures.stop))
        throw std::invalid_argument("FLIP: the exposures must be finite, at least one");
    std::vector<float> worst(size_t(reference.width) * reference.height, 0.0f);
    const double step = (exposures.stop - exposures.start) / std::max(exposures.count - 1, 1);
    for (int k = 0; k < exposures.count; ++k) {
        const double exposure = exposures.start + k * step;
        const std::vector<float> e =
            ldrFlip(toneMapped(reference, exposure), toneMapped(test, exposure), ppd);
        for (size_t i = 0; i < worst.size(); ++i) worst[i] = std::max(worst[i], e[i]);
    }
    return worst;
}

}  // namespace nenrin
