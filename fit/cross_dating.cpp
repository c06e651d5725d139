#include "fit/cross_dating.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <vector>

#include "renderer/parallel_tiles.h"
#include "renderer/stats/ndimage_filters.h"
#include "util/axis_frame.h"

namespace nenrin {

namespace {

constexpr double kShell = 2e-4;    // m
constexpr double kBlur = 6;        // px of 256: what is taken out of L* (stains, light)
constexpr int kLeastShared = 25;   // shells two faces must share to be compared
constexpr int kLeastPerShell = 3;  // pixels a shell mean needs
constexpr double kNearest = 0.002, kFarthest = 2.0;
constexpr int kRadii = 40, kAngles = 72;
constexpr double kMisfitSlack = 2;  // degrees

struct Pixel {
    Vec3 position;
    double ring;  ///< L* less its blur
    int face;
};

std::vector<Pixel> ringPixels(std::span<const FacePhoto> faces) {
    std::vector<Pixel> pixels;
    for (size_t f = 0; f < faces.size(); ++f) {
        const Plane& l = faces[f].lightness;
        const Plane blurred = gaussianFilter(l, kBlur);
        for (int y = 2; y < l.height - 2; y += 2)
            for (int x = 2; x < l.width - 2; x += 2)
                pixels.push_back({faces[f].position(x, y), l.at(x, y) - blurred.at(x, y), int(f)});
    }
    return pixels;
}

double agreement(const PithLine& pith, std::span<const Pixel> pixels, int faceCount) {
    std::vector<double> radius(pixels.size());
    double inner = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < pixels.size(); ++i)
        inner = std::min(inner, radius[i] = ringRadius(pith, pixels[i].position));
    const size_t faces = size_t(faceCount);
    std::vector<std::vector<double>> sum(faces), count(faces);
    for (size_t i = 0; i < pixels.size(); ++i) {
        const size_t b = size_t((radius[i] - inner) / kShell);
        auto& s = sum[size_t(pixels[i].face)];
        auto& c = count[size_t(pixels[i].face)];
        if (b >= s.size()) s.resize(b + 1, 0), c.resize(b + 1, 0);
        s[b] += pixels[i].ring, c[b] += 1;
    }
    double total = 0, weights = 0;
    for (int a = 0; a < faceCount; ++a)
        for (int b = a + 1; b < faceCount; ++b) {
            double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0, n = 0;
            const size_t shells = std::min(sum[size_t(a)].size(), sum[size_t(b)].size());
            for (size_t k = 0; k < shells; ++k) {
                if (count[size_t(a)][k] < kLeastPerShell || count[size_t(b)][k] < kLeastPerShell)
                    continue;
                const double x = sum[size_t(a)][k] / count[size_t(a)][k];
                const double y = sum[size_t(b)][k] / count[size_t(b)][k];
                sa += x, sb += y, saa += x * x, sbb += y * y, sab += x * y, n += 1;
            }
            if (n < kLeastShared) continue;
            const double cov = sab / n - sa / n * sb / n;
            const double va = saa / n - sa / n * sa / n, vb = sbb / n - sb / n * sb / n;
            if (!(va > 0 && vb > 0)) continue;
            total += n * cov / std::sqrt(va * vb), weights += n;
        }
    return weights > 0 ? total / weights : 0;
}

}  // namespace

PithLine crossDatePithLine(const PithLine& pith, std::span<const FacePhoto> faces, int threads,
                           double margin) {
    if (faces.size() < 2) return pith;
    const std::vector<Pixel> pixels = ringPixels(faces);
    const int faceCount = int(faces.size());
    const AxisFrame frame(pith.direction);
    auto lineAt = [&](double u, double v) {
        PithLine l = pith;
        l.point = frame.s * u + frame.t * v;  // across the line from the sample's centre
        l.distance = std::hypot(u, v);
        return l;
    };
    struct Place {
        double score, u, v, step;
    };
    // The polar grid, its radii log-spaced: the step across it grows with the distance.
    std::vector<Place> grid(size_t(kRadii) * kAngles);
    parallelTiles(grid.size(), threads, [&](size_t g) {
        const int i = int(g) / kAngles, k = int(g) % kAngles;
        const double r = kNearest * std::pow(kFarthest / kNearest, i / double(kRadii - 1));
        const double a = 2 * std::numbers::pi * k / kAngles;
        const double u = r * std::cos(a), v = r * std::sin(a);
        grid[g] = {agreement(lineAt(u, v), pixels, faceCount), u, v,
                   std::max(r * 2 * std::numbers::pi / kAngles, 5e-4)};
    });
    std::sort(grid.begin(), grid.end(), [](const Place& a, const Place& b) {
        return a.score > b.score || (a.score == b.score && a.u < b.u);
    });
    // Finer grids around the best few places the ring directions allow: fitting them no more
    // than kMisfitSlack degrees worse than the line, and not inside the sample when the line
    // is outside it (a line through the sample's middle puts every face at about the same
    // radii, and their patterns agree by chance).
    double sampleRadius = 0;
    for (const Pixel& p : pixels)
        sampleRadius = std::max(
            sampleRadius, length(p.position - pith.direction * dot(p.position, pith.direction)));
    const double nearest = pith.distance > sampleRadius ? sampleRadius : 0.0;
    const double allowed = pith.medianMisfitDeg + kMisfitSlack;
    auto allowedAt = [&](double u, double v) {
        return std::hypot(u, v) >= nearest && pithMisfitDeg(lineAt(u, v), faces) <= allowed;
    };
    Place best{-2, 0, 0, 0};
    int tried = 0;
    for (size_t c = 0; c < grid.size() && tried < 5; ++c) {
        if (!allowedAt(grid[c].u, grid[c].v)) continue;
        ++tried;
        Place at = grid[c];
        for (double step = at.step / 2; step > 2e-4; step /= 4) {
            const Place from = at;
            std::array<double, 81> scores;
            parallelTiles(scores.size(), threads, [&](size_t k) {
                const double u = from.u + (int(k) / 9 - 4) * step;
                const double v = from.v + (int(k) % 9 - 4) * step;
                scores[k] = agreement(lineAt(u, v), pixels, faceCount);
            });
            // The best-agreeing place the directions allow (their misfit is the costly test).
            std::array<size_t, 81> order;
            std::iota(order.begin(), order.end(), size_t{0});
            std::stable_sort(order.begin(), order.end(),
                             [&](size_t a, size_t b) { return scores[a] > scores[b]; });
            for (const size_t k : order) {
                if (!(scores[k] > at.score)) break;
                const double u = from.u + (int(k) / 9 - 4) * step;
                const double v = from.v + (int(k) % 9 - 4) * step;
                if (allowedAt(u, v)) {
                    at = {scores[k], u, v, step};
                    break;
                }
            }
        }
        if (at.score > best.score) best = at;
    }
    const double current = agreement(pith, pixels, faceCount);
    if (!(best.score > current + margin)) return pith;
    PithLine out = lineAt(best.u, best.v);
    out.medianMisfitDeg = pithMisfitDeg(out, faces);
    return out;
}

}  // namespace nenrin
