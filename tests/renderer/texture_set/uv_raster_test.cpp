#include "renderer/texture_set/uv_raster.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numeric>
#include <stdexcept>
#include <string>

namespace nenrin {
namespace {

/// A flat mesh whose positions are its uvs (z = 0), one triangle per corner triple.
TriangleMesh uvMesh(const std::vector<std::array<double, 2>>& uvs,
                    const std::vector<std::array<uint32_t, 3>>& triangles) {
    TriangleMesh m;
    for (const auto& uv : uvs) m.positions.push_back({uv[0], uv[1], 0});
    m.uvs = uvs;
    m.triangles = triangles;
    return m;
}

/// The uv at texel (i, j)'s sample point as the barycentrics of its triangle give it.
std::array<double, 2> sampledUv(const TriangleMesh& m, const UvRaster& r, size_t idx) {
    const auto& tri = m.triangles[r.triangle[idx]];
    std::array<double, 2> uv{0, 0};
    for (int k = 0; k < 3; ++k) {
        uv[0] += r.barycentric[idx][k] * m.uvs[tri[k]][0];
        uv[1] += r.barycentric[idx][k] * m.uvs[tri[k]][1];
    }
    return uv;
}

std::array<double, 2> texelCentre(int i, int j, int w, int h) {
    return {(i + 0.5) / w, 1 - (j + 0.5) / h};
}

size_t coveredCount(const UvRaster& r) {
    auto c = r.covered();
    return static_cast<size_t>(std::accumulate(c.begin(), c.end(), 0));
}

TEST(UvRaster, HalfSquareCoversTexelsWhoseCentreIsInside) {
    // u + v <= 1: in image rows (row 0 at v = 1) the lower-left half, j >= i. The centres with
    // j == i lie exactly on the hypotenuse, a right (not top-left) edge: they are edge texels.
    TriangleMesh m = uvMesh({{0, 0}, {1, 0}, {0, 1}}, {{0, 1, 2}});
    UvRaster r = rasterizeUv(m, 8, 8);
    ASSERT_EQ(r.triangle.size(), 64u);
    EXPECT_EQ(r.overlappingTexels, 0u);
    EXPECT_EQ(r.degenerateTriangles, 0u);
    EXPECT_EQ(r.trianglesOutsideUnitSquare, 0u);
    EXPECT_EQ(r.edgeTexels, 8u);
    for (int j = 0; j < 8; ++j) {
        for (int i = 0; i < 8; ++i) {
            size_t idx = j * 8 + i;
            auto centre = texelCentre(i, j, 8, 8);
            bool inside = centre[0] + centre[1] < 1;
            bool onEdge = centre[0] + centre[1] == 1;
            if (!inside && !onEdge) {
                // Squares above the diagonal touch the triangle at one corner at most.
                EXPECT_EQ(r.triangle[idx], -1) << i << "," << j;
                continue;
            }
            ASSERT_EQ(r.triangle[idx], 0) << i << "," << j;
            const auto& b = r.barycentric[idx];
            EXPECT_NEAR(b[0] + b[1] + b[2], 1, 1e-12);
            for (double w : b) EXPECT_GE(w, 0);
            auto uv = sampledUv(m, r, idx);
            EXPECT_NEAR(uv[0], centre[0], 1e-12) << i << "," << j;
            EXPECT_NEAR(uv[1], centre[1], 1e-12) << i << "," << j;
        }
    }
    EXPECT_EQ(coveredCount(r), 36u);
}

TEST(UvRaster, BarycentricsReproduceCentresOnANonSquareMap) {
    // A generic triangle on a 37 x 23 map: interior texels sample their own centre.
    TriangleMesh m = uvMesh({{0.13, 0.07}, {0.91, 0.31}, {0.42, 0.96}}, {{0, 2, 1}});
    UvRaster r = rasterizeUv(m, 37, 23);
    size_t interior = 0;
    for (int j = 0; j < 23; ++j) {
        for (int i = 0; i < 37; ++i) {
            size_t idx = j * 37 + i;
            if (r.triangle[idx] < 0) continue;
            auto uv = sampledUv(m, r, idx);
            auto centre = texelCentre(i, j, 37, 23);
            bool atCentre =
                std::abs(uv[0] - centre[0]) < 1e-12 && std::abs(uv[1] - centre[1]) < 1e-12;
            if (atCentre) ++interior;
            // Edge texels sample a point of the triangle within a texel's diagonal.
            EXPECT_LT(std::hypot((uv[0] - centre[0]) * 37, (uv[1] - centre[1]) * 23), 0.7072);
        }
    }
    EXPECT_EQ(interior + r.edgeTexels, coveredCount(r));
    EXPECT_GT(interior, 200u);
    EXPECT_GT(r.edgeTexels, 0u);
}

TEST(UvRaster, TwoTrianglesFormingTheSquareCoverEveryTexelOnce) {
    // The shared diagonal passes through texel centres at 8x8; odd sizes test other cases.
    for (auto [w, h] : {std::pair{8, 8}, std::pair{7, 5}, std::pair{64, 64}}) {
        TriangleMesh m = uvMesh({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{0, 1, 2}, {0, 2, 3}});
        UvRaster r = rasterizeUv(m, w, h);
        EXPECT_EQ(r.overlappingTexels, 0u);
        EXPECT_EQ(r.edgeTexels, 0u);
        EXPECT_EQ(coveredCount(r), static_cast<size_t>(w * h));
        for (size_t idx = 0; idx < r.triangle.size(); ++idx) {
            int i = static_cast<int>(idx % w), j = static_cast<int>(idx / w);
            auto uv = sampledUv(m, r, idx);
            auto centre = texelCentre(i, j, w, h);
            EXPECT_NEAR(uv[0], centre[0], 1e-12);
            EXPECT_NEAR(uv[1], centre[1], 1e-12);
        }
    }
}

TEST(UvRaster, ClosedFanHasNoHolesAndNoDoubleCoverage) {
    // Eight triangles around the map's centre (a texel centre at odd sizes), windings mixed.
    std::vector<std::array<double, 2>> uvs = {{0.5, 0.5}};
    std::vector<std::array<uint32_t, 3>> tris;
    const double ring[8][2] = {{0, 0}, {0.5, 0}, {1, 0}, {1, 0.5},
                               {1, 1}, {0.5, 1}, {0, 1}, {0, 0.5}};
    for (const auto& p : ring) uvs.push_back({p[0], p[1]});
    for (uint32_t k = 0; k < 8; ++k) {
        uint32_t a = 1 + k, b = 1 + (k + 1) % 8;
        tris.push_back(k % 2 ? std::array<uint32_t, 3>{0, a, b} : std::array<uint32_t, 3>{b, a, 0});
    }
    TriangleMesh m = uvMesh(uvs, tris);
    for (int size : {4, 5, 16}) {
        UvRaster r = rasterizeUv(m, size, size);
        EXPECT_EQ(r.overlappingTexels, 0u) << size;
        EXPECT_EQ(r.edgeTexels, 0u) << size;
        EXPECT_EQ(coveredCount(r), static_cast<size_t>(size * size)) << size;
    }
}

TEST(UvRaster, DuplicatedTriangleReportsOverlapAndTheFirstWins) {
    TriangleMesh m = uvMesh({{0, 0}, {1, 0}, {0, 1}}, {{0, 1, 2}, {0, 2, 1}});
    UvRaster r = rasterizeUv(m, 8, 8);
    EXPECT_EQ(r.overlappingTexels, 28u);  // the centres strictly inside (j > i)
    for (int32_t t : r.triangle) EXPECT_LE(t, 0);
}

TEST(UvRaster, UvsOutsideTheUnitSquareAreCountedAndClipped) {
    TriangleMesh m = uvMesh({{-3, -2}, {5, -1}, {0.5, 40}, {0.2, 0.2}, {0.8, 0.2}, {0.5, 0.8}},
                            {{0, 1, 2}, {3, 4, 5}});
    UvRaster r = rasterizeUv(m, 16, 16);
    EXPECT_EQ(r.trianglesOutsideUnitSquare, 1u);
    EXPECT_EQ(coveredCount(r), 256u);  // the big triangle contains the whole map
    // Every centre of the small triangle is also in the big one (index 0, which keeps them).
    UvRaster small = rasterizeUv(uvMesh(m.uvs, {{3, 4, 5}}), 16, 16);
    EXPECT_EQ(r.overlappingTexels, coveredCount(small) - small.edgeTexels);
    EXPECT_GT(r.overlappingTexels, 0u);
    for (int32_t t : r.triangle) EXPECT_EQ(t, 0);

    // Entirely off the map, and huge: nothing covered, no crash.
    TriangleMesh far = uvMesh({{1e12, 1e12}, {2e12, 1e12}, {1e12, 3e12}}, {{0, 1, 2}});
    UvRaster rf = rasterizeUv(far, 16, 16);
    EXPECT_EQ(rf.trianglesOutsideUnitSquare, 1u);
    EXPECT_EQ(coveredCount(rf), 0u);
}

TEST(UvRaster, DegenerateTrianglesAreCountedAndSkipped) {
    TriangleMesh m = uvMesh({{0, 0}, {0.5, 0.5}, {1, 1}, {0.3, 0.7}},
                            {{0, 1, 2}, {3, 3, 3}, {0, 0, 2}, {0, 2, 3}});
    UvRaster r = rasterizeUv(m, 8, 8);
    EXPECT_EQ(r.degenerateTriangles, 3u);
    for (int32_t t : r.triangle) EXPECT_TRUE(t == -1 || t == 3);
    EXPECT_GT(coveredCount(r), 0u);
}

TEST(UvRaster, RejectsMissingUvsAndBadSizes) {
    TriangleMesh m = uvMesh({{0, 0}, {1, 0}, {0, 1}}, {{0, 1, 2}});
    EXPECT_THROW(rasterizeUv(m, 0, 8), std::invalid_argument);
    EXPECT_THROW(rasterizeUv(m, 8, -1), std::invalid_argument);
    TriangleMesh noUvs = m;
    noUvs.uvs.clear();
    EXPECT_THROW(rasterizeUv(noUvs, 8, 8), std::invalid_argument);
    TriangleMesh badIndex = m;
    badIndex.triangles[0][2] = 7;
    EXPECT_THROW(rasterizeUv(badIndex, 8, 8), std::invalid_argument);
}

TEST(UvRaster, DilationGrowsAnIslandByExactlyNRings) {
    const int w = 21, h = 17, cx = 9, cy = 8, channels = 2;
    std::vector<float> pixels(w * h * channels, -7.0f);
    std::vector<uint8_t> covered(w * h, 0);
    covered[cy * w + cx] = 1;
    pixels[(cy * w + cx) * channels] = 0.25f;
    pixels[(cy * w + cx) * channels + 1] = 3.5f;
    for (int n : {0, 1, 3}) {
        std::vector<float> p = pixels;
        std::vector<uint8_t> c = covered;
        dilate(p, channels, w, h, c, n);
        EXPECT_EQ(std::accumulate(c.begin(), c.end(), 0), (2 * n + 1) * (2 * n + 1)) << n;
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                size_t idx = y * w + x;
                bool inRing = std::abs(x - cx) <= n && std::abs(y - cy) <= n;
                EXPECT_EQ(c[idx], inRing ? 1 : 0);
                EXPECT_EQ(p[idx * channels], inRing ? 0.25f : -7.0f);
                EXPECT_EQ(p[idx * channels + 1], inRing ? 3.5f : -7.0f);
            }
        }
    }
}

TEST(UvRaster, DilationAveragesNeighboursAndStopsAtTheBorder) {
    // Two covered texels side by side: the texels above both take the average; a ring clipped
    // by the map border still grows; more rings than fit leave the whole map covered.
    const int w = 4, h = 3;
    std::vector<float> p(w * h, 0.0f);
    std::vector<uint8_t> c(w * h, 0);
    c[0 * w + 1] = c[0 * w + 2] = 1;
    p[0 * w + 1] = 1.0f;
    p[0 * w + 2] = 3.0f;
    dilate(p, 1, w, h, c, 1);
    EXPECT_EQ(p[1 * w + 1], 2.0f);  // neighbours (1,0) and (2,0)
    EXPECT_EQ(p[0 * w + 0], 1.0f);
    EXPECT_EQ(p[1 * w + 3], 3.0f);
    EXPECT_EQ(c[2 * w + 1], 0);
    EXPECT_EQ(std::accumulate(c.begin(), c.end(), 0), 8);
    dilate(p, 1, w, h, c, 10);
    EXPECT_EQ(std::accumulate(c.begin(), c.end(), 0), w * h);

    std::vector<float> bad(5);
    EXPECT_THROW(dilate(bad, 1, w, h, c, 1), std::invalid_argument);
}

TEST(UvRaster, DilationIsDeterministic) {
    TriangleMesh m = uvMesh({{0.1, 0.1}, {0.7, 0.2}, {0.3, 0.8}, {0.75, 0.6}, {0.95, 0.9}},
                            {{0, 1, 2}, {1, 3, 4}});
    UvRaster r = rasterizeUv(m, 64, 48);
    std::vector<float> pixels(64 * 48 * 3, 0.0f);
    for (size_t idx = 0; idx < r.triangle.size(); ++idx) {
        for (int ch = 0; ch < 3; ++ch) {
            pixels[idx * 3 + ch] = static_cast<float>(std::sin(0.37 * idx + ch) * 0.5 + 0.5);
        }
    }
    std::vector<float> a = pixels, b = pixels;
    std::vector<uint8_t> ca = r.covered(), cb = r.covered();
    dilate(a, 3, 64, 48, ca, 4);
    dilate(b, 3, 64, 48, cb, 4);
    EXPECT_EQ(a, b);
    EXPECT_EQ(ca, cb);
    UvRaster again = rasterizeUv(m, 64, 48);
    EXPECT_EQ(again.triangle, r.triangle);
    EXPECT_EQ(again.barycentric, r.barycentric);
}

TEST(UvRaster, ShippedTableTop) {
    TriangleMesh m = loadObjMesh(std::string(NENRIN_SOURCE_DIR) + "/scenes/meshes/table-top.obj");
    UvRaster r = rasterizeUv(m, 256, 256);
    EXPECT_EQ(r.overlappingTexels, 0u);
    EXPECT_EQ(r.trianglesOutsideUnitSquare, 0u);
    double share = static_cast<double>(coveredCount(r)) / (256 * 256);
    EXPECT_GT(share, 0.3);
    EXPECT_LE(share, 1.0);
}

TEST(UvRaster, LargeGridChartHasNoHolesAndNoOverlaps) {
    // 10k triangles of a 50 x 100 grid chart on a 2048^2 map.
    std::vector<std::array<double, 2>> uvs;
    std::vector<std::array<uint32_t, 3>> tris;
    const int nx = 50, ny = 100;
    for (int y = 0; y <= ny; ++y) {
        for (int x = 0; x <= nx; ++x) uvs.push_back({0.02 + 0.96 * x / nx, 0.02 + 0.96 * y / ny});
    }
    for (int y = 0; y < ny; ++y) {
        for (int x = 0; x < nx; ++x) {
            uint32_t a = y * (nx + 1) + x, b = a + 1, c = a + nx + 1, d = c + 1;
            tris.push_back({a, b, d});
            tris.push_back({a, d, c});
        }
    }
    TriangleMesh m = uvMesh(uvs, tris);
    UvRaster r = rasterizeUv(m, 2048, 2048);
    EXPECT_EQ(r.overlappingTexels, 0u);
    // Every texel whose centre lies inside the chart is covered (its speed is measured by
    // BM_UvBake in nenrin_bench, not here).
    size_t holes = 0;
    for (int j = 0; j < 2048; ++j)
        for (int i = 0; i < 2048; ++i) {
            double u = (i + 0.5) / 2048, v = 1 - (j + 0.5) / 2048;
            if (u > 0.02 && u < 0.98 && v > 0.02 && v < 0.98 &&
                r.triangle[size_t(j) * 2048 + i] < 0)
                ++holes;
        }
    EXPECT_EQ(holes, 0u);
}

}  // namespace
}  // namespace nenrin
