#include "renderer/texture_set/uv_raster.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace nenrin {

namespace {

struct Point {
    double x, y;
};

/// One edge's function, oriented so that the triangle's interior is positive. The endpoints are
/// stored in a canonical (lexicographic) order whatever the triangle's winding, so the two
/// triangles of a shared edge compute bit-identical products and differ only by the (exact)
/// sign: a centre on the edge is zero for both, and never positive for both.
struct Edge {
    Point origin, dir;
    double sign = 1;       ///< +1 or -1
    bool topLeft = false;  ///< a centre exactly on the edge belongs to this triangle

    double operator()(Point p) const {
        return sign * (dir.x * (p.y - origin.y) - dir.y * (p.x - origin.x));
    }
    /// x and y gradients of operator().
    double gx() const { return -sign * dir.y; }
    double gy() const { return sign * dir.x; }
};

/// The edge from a to b with sign `orient` (+1 when the triangle a, b, c has positive area).
Edge makeEdge(Point a, Point b, double orient) {
    Edge e;
    bool swapped = b.x < a.x || (b.x == a.x && b.y < a.y);
    e.origin = swapped ? b : a;
    Point to = swapped ? a : b;
    e.dir = {to.x - e.origin.x, to.y - e.origin.y};
    e.sign = swapped ? -orient : orient;
    // Direction of travel with the interior on the positive side; in image space (y down) a
    // top edge runs +x, a left edge runs -y. Exactly one of d and -d qualifies.
    double dx = orient * (b.x - a.x), dy = orient * (b.y - a.y);
    e.topLeft = dy < 0 || (dy == 0 && dx > 0);
    return e;
}

bool insideEdge(const Edge& e, double value) { return value > 0 || (value == 0 && e.topLeft); }

/// Texel index range [lo, hi] whose squares overlap (min, max) with positive length.
void texelRange(double min, double max, int size, int& lo, int& hi) {
    // Clamp before converting: uvs far outside the map must not overflow int.
    double l = std::floor(std::clamp(min, -1.0, size + 1.0));
    double h = std::ceil(std::clamp(max, -1.0, size + 1.0)) - 1;
    lo = std::max(0, static_cast<int>(l));
    hi = std::min(size - 1, static_cast<int>(h));
}

/// Closest point of the triangle's boundary to p: squared distance and corner weights.
double closestOnBoundary(const Point (&c)[3], Point p, std::array<double, 3>& weights) {
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
        const Point& a = c[(k + 1) % 3];
        const Point& b = c[(k + 2) % 3];
        double ex = b.x - a.x, ey = b.y - a.y;
        double len2 = ex * ex + ey * ey;
        double t = len2 > 0 ? ((p.x - a.x) * ex + (p.y - a.y) * ey) / len2 : 0.0;
        t = std::clamp(t, 0.0, 1.0);
        double qx = a.x + t * ex - p.x, qy = a.y + t * ey - p.y;
        double d2 = qx * qx + qy * qy;
        if (d2 < best) {
            best = d2;
            weights[k] = 0;
            weights[(k + 1) % 3] = 1 - t;
            weights[(k + 2) % 3] = t;
        }
    }
    return best;
}

enum TexelState : uint8_t { kEmpty, kEdge, kInterior, kOverlapped };

/// The input's problems are programming errors: callers check uvs and sizes first.
void checkRasterInput(const TriangleMesh& mesh, int width, int height) {
    if (mesh.uvs.empty()) throw std::invalid_argument("rasterizeUv: the mesh has no uvs");
    if (width < 1 || height < 1) {
        throw std::invalid_argument("rasterizeUv: map size " + std::to_string(width) + "x" +
                                    std::to_string(height) + " (must be at least 1x1)");
    }
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        for (uint32_t v : mesh.triangles[t]) {
            if (v >= mesh.uvs.size()) {
                throw std::invalid_argument("rasterizeUv: triangle " + std::to_string(t) +
                                            " indexes uv " + std::to_string(v) + " of " +
                                            std::to_string(mesh.uvs.size()));
            }
        }
    }
}

/// The texels of triangle `id` (corners c in texel space, edge functions e, twice its area):
/// those whose centre it holds (interior; the lowest index keeps a texel two hold), and those
/// its edges only cross, given to the triangle whose boundary is nearest the centre.
void coverTexels(const Point (&c)[3], const Edge (&e)[3], double area, int32_t id, UvRaster& r,
                 std::vector<uint8_t>& state, std::vector<double>& edgeDistance) {
    const int width = r.width;
    // Half the texel square's extent along each edge function (its gradient's L1 norm / 2).
    double halfExtent[3];
    for (int k = 0; k < 3; ++k) halfExtent[k] = 0.5 * (std::abs(e[k].gx()) + std::abs(e[k].gy()));
    int i0, i1, j0, j1;
    texelRange(std::min({c[0].x, c[1].x, c[2].x}), std::max({c[0].x, c[1].x, c[2].x}), r.width, i0,
               i1);
    texelRange(std::min({c[0].y, c[1].y, c[2].y}), std::max({c[0].y, c[1].y, c[2].y}), r.height, j0,
               j1);
    for (int j = j0; j <= j1; ++j) {
        for (int i = i0; i <= i1; ++i) {
            const Point p{i + 0.5, j + 0.5};
            const size_t idx = static_cast<size_t>(j) * width + i;
            double w[3] = {e[0](p), e[1](p), e[2](p)};
            if (insideEdge(e[0], w[0]) && insideEdge(e[1], w[1]) && insideEdge(e[2], w[2])) {
                if (state[idx] >= kInterior) {
                    // Lowest index wins: the earlier triangle keeps the texel.
                    if (state[idx] == kInterior) ++r.overlappingTexels;
                    state[idx] = kOverlapped;
                    continue;
                }
                state[idx] = kInterior;
                r.triangle[idx] = id;
                // Normalised by the sum (not the area) so the weights sum to 1.
                double sum = w[0] + w[1] + w[2];
                r.barycentric[idx] = {w[0] / sum, w[1] / sum, w[2] / sum};
                continue;
            }
            if (state[idx] >= kInterior) continue;
            // Separating axes: the bounding box is shared by construction of the range;
            // the square must reach strictly into the triangle along each edge normal.
            bool touches = true;
            for (int k = 0; k < 3 && touches; ++k) {
                touches = w[k] + halfExtent[k] > 0 && w[k] - halfExtent[k] < area;
            }
            if (!touches) continue;
            std::array<double, 3> weights{};
            double d2 = closestOnBoundary(c, p, weights);
            if (d2 < edgeDistance[idx]) {  // strict: ties stay with the lower index
                edgeDistance[idx] = d2;
                state[idx] = kEdge;
                r.triangle[idx] = id;
                r.barycentric[idx] = weights;
            }
        }
    }
}

}  // namespace

std::vector<uint8_t> UvRaster::covered() const {
    std::vector<uint8_t> c(triangle.size());
    for (size_t i = 0; i < triangle.size(); ++i) c[i] = triangle[i] >= 0 ? 1 : 0;
    return c;
}

UvRaster rasterizeUv(const TriangleMesh& mesh, int width, int height) {
    checkRasterInput(mesh, width, height);

    UvRaster r;
    r.width = width;
    r.height = height;
    const size_t count = static_cast<size_t>(width) * static_cast<size_t>(height);
    r.triangle.assign(count, -1);
    r.barycentric.assign(count, {0.0, 0.0, 0.0});
    std::vector<uint8_t> state(count, kEmpty);
    // Squared distance (texel units) from an edge texel's centre to its triangle.
    std::vector<double> edgeDistance(count, std::numeric_limits<double>::infinity());

    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& tri = mesh.triangles[t];
        const std::array<double, 2>* uv[3] = {&mesh.uvs[tri[0]], &mesh.uvs[tri[1]],
                                              &mesh.uvs[tri[2]]};
        bool outside = false;
        for (const auto* q : uv) {
            for (double c : *q) outside = outside || !(c >= 0 && c <= 1);
        }
        if (outside) ++r.trianglesOutsideUnitSquare;

        double uvArea = ((*uv[1])[0] - (*uv[0])[0]) * ((*uv[2])[1] - (*uv[0])[1]) -
                        ((*uv[1])[1] - (*uv[0])[1]) * ((*uv[2])[0] - (*uv[0])[0]);
        // Texel space: x along u, y down from v = 1; texel centres are at half-integers.
        Point c[3];
        for (int k = 0; k < 3; ++k) c[k] = {(*uv[k])[0] * width, (1 - (*uv[k])[1]) * height};
        // The winding from the same canonical edge function the texels use, so that the
        // orientation never disagrees with the per-texel signs for slivers.
        double rawArea = makeEdge(c[1], c[2], 1)(c[0]);
        if (uvArea == 0 || rawArea == 0 || !std::isfinite(uvArea) || !std::isfinite(rawArea)) {
            ++r.degenerateTriangles;
            continue;
        }
        const double orient = rawArea > 0 ? 1 : -1;
        const Edge e[3] = {makeEdge(c[1], c[2], orient), makeEdge(c[2], c[0], orient),
                           makeEdge(c[0], c[1], orient)};
        const double area = std::abs(rawArea);
        coverTexels(c, e, area, static_cast<int32_t>(t), r, state, edgeDistance);
    }
    r.edgeTexels = static_cast<size_t>(std::count(state.begin(), state.end(), kEdge));
    return r;
}

void dilate(std::vector<float>& pixels, int channels, int width, int height,
            std::vector<uint8_t>& covered, int texels) {
    if (channels < 1 || width < 1 || height < 1 || texels < 0) {
        throw std::invalid_argument("dilate: channels, width and height must be >= 1, texels >= 0");
    }
    const size_t count = static_cast<size_t>(width) * static_cast<size_t>(height);
    if (covered.size() != count || pixels.size() != count * static_cast<size_t>(channels)) {
        throw std::invalid_argument("dilate: pixels/covered do not match the map size");
    }
    static constexpr int kDx[8] = {-1, 0, 1, -1, 1, -1, 0, 1};
    static constexpr int kDy[8] = {-1, -1, -1, 0, 0, 1, 1, 1};

    // The frontier: texels covered by the previous ring (at first, every covered texel). Only
    // their uncovered neighbours can join the next ring, so a ring costs its own size.
    std::vector<size_t> frontier;
    for (size_t idx = 0; idx < count; ++idx) {
        if (covered[idx]) frontier.push_back(idx);
    }
    std::vector<uint8_t> queued(count, 0);
    std::vector<size_t> ring;
    std::vector<float> values;
    std::vector<double> sum(channels);
    for (int pass = 0; pass < texels && !frontier.empty(); ++pass) {
        ring.clear();
        for (size_t f : frontier) {
            const int x = static_cast<int>(f % width), y = static_cast<int>(f / width);
            for (int n = 0; n < 8; ++n) {
                const int nx = x + kDx[n], ny = y + kDy[n];
                if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
                const size_t nIdx = static_cast<size_t>(ny) * width + nx;
                if (covered[nIdx] || queued[nIdx]) continue;
                queued[nIdx] = 1;
                ring.push_back(nIdx);
            }
        }
        // Averages read only texels covered before this ring (covered is not updated until all
        // are computed), summed in the fixed neighbour order above.
        values.resize(ring.size() * channels);
        for (size_t r = 0; r < ring.size(); ++r) {
            const int x = static_cast<int>(ring[r] % width), y = static_cast<int>(ring[r] / width);
            std::fill(sum.begin(), sum.end(), 0.0);
            int n = 0;
            for (int k = 0; k < 8; ++k) {
                const int nx = x + kDx[k], ny = y + kDy[k];
                if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
                const size_t nIdx = static_cast<size_t>(ny) * width + nx;
                if (!covered[nIdx]) continue;
                ++n;
                for (int ch = 0; ch < channels; ++ch) sum[ch] += pixels[nIdx * channels + ch];
            }
            for (int ch = 0; ch < channels; ++ch) {
                values[r * channels + ch] = static_cast<float>(sum[ch] / n);
            }
        }
        for (size_t r = 0; r < ring.size(); ++r) {
            covered[ring[r]] = 1;
            std::copy_n(values.begin() + r * channels, channels,
                        pixels.begin() + ring[r] * channels);
        }
        frontier.swap(ring);
    }
}

}  // namespace nenrin
