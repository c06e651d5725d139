#include "renderer/products/laminated_product.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "util/hash.h"

namespace nenrin {

namespace {

/// Fills a lamella's box and its map from product space (board centre at 0, length along x,
/// width along y, thickness along z).
Lamella makeLamella(const Vec3& lower, const Vec3& upper, int lengthAxis) {
    Lamella l;
    l.lower = lower;
    l.upper = upper;
    l.lengthAxis = lengthAxis;
    Vec3 along = lengthAxis == 0 ? Vec3{1, 0, 0} : Vec3{0, 0, 1};
    Vec3 across = lengthAxis == 0 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
    RigidTransform productFromLamella =
        RigidTransform::fromAxes(along, across, cross(along, across), (lower + upper) * 0.5);
    l.lamellaFromProduct = productFromLamella.inverse();
    return l;
}

/// Index of the first boundary >= v (clamped to the last interval).
size_t intervalOf(const std::vector<double>& upperEnds, double v) {
    auto it = std::lower_bound(upperEnds.begin(), upperEnds.end(), v);
    return std::min<size_t>(it - upperEnds.begin(), upperEnds.size() - 1);
}

double triangleWave(double x) {
    double f = x - std::floor(x);
    return f < 0.5 ? 2 * f : 2 * (1 - f);
}

/// Adds one layer of strips along `stripAxis`, each strip one piece per entry of pieceEnds.
void addLayer(LaminatedLayout& layout, double y0, double y1, int lengthAxis,
              const std::vector<double>& stripEnds,
              const std::vector<std::vector<double>>& pieceEnds) {
    LaminatedLayout::Layer layer{y0, y1, lengthAxis, {}};
    const Vec3 half = layout.size * 0.5;
    const int stripAxis = lengthAxis == 0 ? 2 : 0;
    double s0 = -half[stripAxis];
    for (size_t s = 0; s < stripEnds.size(); ++s) {
        LaminatedLayout::Strip strip{s0, stripEnds[s], pieceEnds[s], {}};
        double p0 = -half[lengthAxis];
        for (double p1 : strip.pieceEnds) {
            Vec3 lo, hi;
            double loA[3], hiA[3];
            loA[1] = y0;
            hiA[1] = y1;
            loA[stripAxis] = s0;
            hiA[stripAxis] = stripEnds[s];
            loA[lengthAxis] = p0;
            hiA[lengthAxis] = p1;
            lo = {loA[0], loA[1], loA[2]};
            hi = {hiA[0], hiA[1], hiA[2]};
            strip.lamellae.push_back(static_cast<uint32_t>(layout.lamellae.size()));
            layout.lamellae.push_back(makeLamella(lo, hi, lengthAxis));
            p0 = p1;
        }
        layer.strips.push_back(std::move(strip));
        s0 = stripEnds[s];
    }
    layout.layers.push_back(std::move(layer));
}

std::vector<double> evenEnds(double total, int count) {
    std::vector<double> ends(count);
    for (int i = 0; i < count; ++i) ends[i] = -0.5 * total + total * (i + 1) / count;
    ends.back() = 0.5 * total;
    return ends;
}

}  // namespace

uint32_t LaminatedLayout::lamellaAt(const Vec3& p) const {
    size_t li = 0;
    while (li + 1 < layers.size() && p.y > layers[li].upper) ++li;
    const Layer& layer = layers[li];
    const int stripAxis = layer.lengthAxis == 0 ? 2 : 0;
    double s = p[stripAxis];
    size_t si = 0;
    while (si + 1 < layer.strips.size() && s > layer.strips[si].upper) ++si;
    const Strip& strip = layer.strips[si];
    double along = p[layer.lengthAxis];
    if (strip.pieceEnds.size() > 1 && fingers.length > 0) {
        // The joint boundary zig-zags across the board: shift the point the other way.
        along -= fingers.length * (triangleWave((s - strip.lower) / fingers.pitch) - 0.5);
    }
    return strip.lamellae[intervalOf(strip.pieceEnds, along)];
}

double LaminatedLayout::glueDistance(const Vec3& p) const {
    double best = std::numeric_limits<double>::infinity();
    size_t li = 0;
    while (li + 1 < layers.size() && p.y > layers[li].upper) ++li;
    const Layer& layer = layers[li];
    if (li > 0) best = std::min(best, std::abs(p.y - layer.lower));
    if (li + 1 < layers.size()) best = std::min(best, std::abs(layer.upper - p.y));
    const int stripAxis = layer.lengthAxis == 0 ? 2 : 0;
    double s = p[stripAxis];
    size_t si = 0;
    while (si + 1 < layer.strips.size() && s > layer.strips[si].upper) ++si;
    const Strip& strip = layer.strips[si];
    if (si > 0) best = std::min(best, std::abs(s - strip.lower));
    if (si + 1 < layer.strips.size()) best = std::min(best, std::abs(strip.upper - s));
    if (strip.pieceEnds.size() > 1) {
        double along = p[layer.lengthAxis];
        if (fingers.length > 0)
            along -= fingers.length * (triangleWave((s - strip.lower) / fingers.pitch) - 0.5);
        // The zig-zag's slope makes the true distance smaller than the one along the board.
        double slope = fingers.length > 0 ? 2 * fingers.length / fingers.pitch : 0;
        double scale = 1 / std::sqrt(1 + slope * slope);
        for (size_t k = 0; k + 1 < strip.pieceEnds.size(); ++k)
            best = std::min(best, std::abs(along - strip.pieceEnds[k]) * scale);
    }
    return best;
}

LaminatedLayout glulamLayout(int count, double thickness, double width, double length,
                             double minPiece, double maxPiece, uint64_t seed) {
    LaminatedLayout layout;
    layout.size = {length, count * thickness, width};
    for (int i = 0; i < count; ++i) {
        std::vector<double> ends;
        if (maxPiece > 0) {
            // Finger-jointed boards of random length; the last piece takes what is left, and a
            // stub shorter than minPiece / 2 is merged into its neighbour.
            SplitMix rng(hashCombine(seed, 0x6a01u + i));
            double at = -0.5 * length;
            // Start mid-board so the joints of neighbouring lamellae are staggered.
            at += rng.uniform(0.2, 0.8) * rng.uniform(minPiece, maxPiece);
            while (at < 0.5 * length - 0.5 * minPiece) {
                ends.push_back(at);
                at += rng.uniform(minPiece, maxPiece);
            }
        }
        ends.push_back(0.5 * length);
        double y0 = -0.5 * layout.size.y + i * thickness;
        addLayer(layout, y0, y0 + thickness, 0, {0.5 * width}, {ends});
    }
    return layout;
}

LaminatedLayout cltLayout(int layers, double thickness, double boardWidth, double length,
                          double width) {
    LaminatedLayout layout;
    layout.size = {length, layers * thickness, width};
    for (int i = 0; i < layers; ++i) {
        int lengthAxis = i % 2 == 0 ? 0 : 2;
        double across = lengthAxis == 0 ? width : length;
        double along = lengthAxis == 0 ? length : width;
        int boards = std::max(1, static_cast<int>(std::ceil(across / boardWidth - 1e-9)));
        std::vector<double> stripEnds = evenEnds(across, boards);
        std::vector<std::vector<double>> pieces(boards, std::vector<double>{0.5 * along});
        double y0 = -0.5 * layout.size.y + i * thickness;
        addLayer(layout, y0, y0 + thickness, lengthAxis, stripEnds, pieces);
    }
    return layout;
}

LaminatedLayout edgeGluedLayout(int boards, double thickness, double width, double length) {
    LaminatedLayout layout;
    layout.size = {length, thickness, width};
    std::vector<std::vector<double>> pieces(boards, std::vector<double>{0.5 * length});
    addLayer(layout, -0.5 * thickness, 0.5 * thickness, 0, evenEnds(width, boards), pieces);
    return layout;
}

}  // namespace nenrin
