#include "renderer/texture_set/uv_bake.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "renderer/parallel_tiles.h"
#include "renderer/texture_set/pbr_finish.h"
#include "util/input_error.h"
#include "util/memory_budget.h"
#include "util/progress.h"

namespace nenrin {

namespace {

constexpr int kTile = 16;

/// Per triangle: the object-space derivatives of position over uv (the tangent frame and the
/// texel footprint come from them).
struct TriangleFrame {
    Vec3 dpdu, dpdv, normal;
    bool valid = false;
};

TriangleFrame triangleFrame(const TriangleMesh& m, uint32_t t) {
    const auto& tri = m.triangles[t];
    Vec3 p0 = m.positions[tri[0]], p1 = m.positions[tri[1]], p2 = m.positions[tri[2]];
    auto uv0 = m.uvs[tri[0]], uv1 = m.uvs[tri[1]], uv2 = m.uvs[tri[2]];
    double du1 = uv1[0] - uv0[0], dv1 = uv1[1] - uv0[1];
    double du2 = uv2[0] - uv0[0], dv2 = uv2[1] - uv0[1];
    double det = du1 * dv2 - du2 * dv1;
    TriangleFrame f;
    f.normal = normalize(cross(p1 - p0, p2 - p0));
    if (std::abs(det) < 1e-30) return f;
    Vec3 e1 = p1 - p0, e2 = p2 - p0;
    f.dpdu = (e1 * dv2 - e2 * dv1) / det;
    f.dpdv = (e2 * du1 - e1 * du2) / det;
    f.valid = true;
    return f;
}

void encodeUnit(float* out, const Vec3& v) {
    out[0] = float(0.5 * v.x + 0.5);
    out[1] = float(0.5 * v.y + 0.5);
    out[2] = float(0.5 * v.z + 0.5);
}

/// Every map at its neutral value: what texels no chart reaches hold. A flat normal, a fibre
/// along +u, the finish's roughness, so a host that samples them (mip-mapping, bilinear
/// lookups) sees neutral values, never a zero vector. The base colour is filled with the mean
/// wood later (fillPastCharts).
void clearMaps(UvMaps& maps) {
    const size_t n = size_t(maps.width) * maps.height;
    const float baseRoughness = float(pbrFinish(maps.finish).baseRoughness);
    maps.baseColour.assign(3 * n, 0);
    maps.coverage.assign(n, 0);
    maps.roughness.assign(n, baseRoughness);
    maps.normal.assign(3 * n, 0);
    maps.fibre.assign(3 * n, 0);
    maps.growth.assign(2 * n, 0);
    for (size_t i = 0; i < n; ++i) {
        encodeUnit(&maps.normal[3 * i], {0, 0, 1});
        encodeUnit(&maps.fibre[3 * i], {1, 0, 0});
    }
}

/// The covered texels of one tile: where each lies in the tree, its surface frame (tangent
/// along +u, bitangent along +v) and its footprint.
struct TileTexels {
    std::vector<size_t> texels;
    std::vector<Vec3> points, normals, tangents, bitangents;
    std::vector<SurfaceFootprint> footprints;
};

/// What every tile reads: the mesh, its triangles' frames and vertex normals, the raster.
struct BakeSurface {
    const TriangleMesh& mesh;
    const std::vector<TriangleFrame>& frames;
    const std::vector<Vec3>& vertexNormals;
    const RigidTransform& treeFromObject;
};

TileTexels gatherTexels(const BakeSurface& surface, const UvMaps& maps, int x0, int y0, int x1,
                        int y1) {
    const TriangleMesh& mesh = surface.mesh;
    TileTexels out;
    for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
            size_t i = size_t(y) * maps.width + x;
            int32_t t = maps.raster.triangle[i];
            if (t < 0 || !surface.frames[t].valid) continue;
            const TriangleFrame& frame = surface.frames[t];
            const auto& tri = mesh.triangles[t];
            const auto& b = maps.raster.barycentric[i];
            const std::vector<Vec3>& vn = surface.vertexNormals;
            Vec3 p = mesh.positions[tri[0]] * b[0] + mesh.positions[tri[1]] * b[1] +
                     mesh.positions[tri[2]] * b[2];
            Vec3 nrm = normalize(vn[tri[0]] * b[0] + vn[tri[1]] * b[1] + vn[tri[2]] * b[2]);
            if (lengthSquared(nrm) == 0) nrm = frame.normal;
            // Tangent along +u, bitangent along +v (mirrored charts flip it), both in the
            // surface: the frame normal maps and fibre maps are expressed in.
            Vec3 tangent = normalize(frame.dpdu - nrm * dot(nrm, frame.dpdu));
            Vec3 bitangent = cross(nrm, tangent);
            if (dot(bitangent, frame.dpdv) < 0) bitangent = -bitangent;
            const RigidTransform& treeFromObject = surface.treeFromObject;
            out.texels.push_back(i);
            out.points.push_back(treeFromObject.point(p));
            out.normals.push_back(nrm);
            out.tangents.push_back(tangent);
            out.bitangents.push_back(bitangent);
            out.footprints.push_back({treeFromObject.vector(frame.dpdu / maps.width),
                                      treeFromObject.vector(frame.dpdv / maps.height), 0,
                                      treeFromObject.vector(nrm)});
        }
    }
    return out;
}

/// The shaded wood of a tile's texels into the maps (normal and fibre in tangent space).
void storeTexels(const TileTexels& tile, const std::vector<WoodSurfaceSample>& samples,
                 const RigidTransform& objectFromTree, const Rgb& boardTint, UvMaps& maps) {
    for (size_t k = 0; k < tile.texels.size(); ++k) {
        size_t i = tile.texels[k];
        const WoodSurfaceSample& s = samples[k];
        // The board's tree tints the albedo, as the renderer does.
        const Rgb albedo =
            multiply(s.coverage > 0 || !(s.albedo == Rgb{}) ? s.albedo : kBarkAlbedo, boardTint);
        maps.baseColour[3 * i] = float(albedo.r);
        maps.baseColour[3 * i + 1] = float(albedo.g);
        maps.baseColour[3 * i + 2] = float(albedo.b);
        maps.coverage[i] = 1;
        const Vec3 &n = tile.normals[k], &t = tile.tangents[k], &bt = tile.bitangents[k];
        // The relief's mean slope over the texel: the host's mip-mapping does the rest.
        Vec3 g = objectFromTree.vector(s.meanReliefGradient);
        Vec3 bumped = normalize(n - (g - n * dot(g, n)));
        encodeUnit(&maps.normal[3 * i], {dot(bumped, t), dot(bumped, bt), dot(bumped, n)});
        Vec3 f = objectFromTree.vector(s.fibre);
        encodeUnit(&maps.fibre[3 * i], {dot(f, t), dot(f, bt), dot(f, n)});
        maps.growth[2 * i] = float(s.T);
        maps.growth[2 * i + 1] = float(s.knot);
    }
}

/// Past the charts: a gutter of `padding` texels grown from them (every map by the same
/// rings, so they stay aligned), and past that the base colour is the mean wood (summed in a
/// fixed order, so the bytes do not depend on the threads), so far mip levels keep the tone.
void fillPastCharts(UvMaps& maps, int padding) {
    const size_t n = size_t(maps.width) * maps.height;
    std::vector<uint8_t> base = maps.raster.covered();
    auto pad = [&](std::vector<float>& pixels, int channels) {
        std::vector<uint8_t> covered = base;
        dilate(pixels, channels, maps.width, maps.height, covered, padding);
    };
    double sum[3] = {0, 0, 0}, count = 0;
    for (size_t i = 0; i < n; ++i)
        if (base[i]) {
            for (int c = 0; c < 3; ++c) sum[c] += maps.baseColour[3 * i + c];
            count += 1;
        }
    if (count > 0)
        for (size_t i = 0; i < n; ++i)
            if (!base[i])
                for (int c = 0; c < 3; ++c) maps.baseColour[3 * i + c] = float(sum[c] / count);
    pad(maps.baseColour, 3);
    pad(maps.normal, 3);
    pad(maps.fibre, 3);
    pad(maps.growth, 2);
}

}  // namespace

UvMaps bakeUvMaps(const Scene& scene, const SceneObject& object, const UvBakeOptions& options) {
    const Material& material = scene.materials[object.material];
    if (object.shape != ShapeType::Mesh || !object.mesh || object.mesh->uvs.empty())
        throw InputError(scene.file, "object \"" + object.name + "\"",
                         "a UV bake needs a mesh object with texture coordinates (vt in an OBJ, "
                         "TEXCOORD_0 in a glTF)");
    if (material.type != MaterialType::Wood)
        throw InputError(scene.file, "object \"" + object.name + "\"",
                         "a UV bake needs an object with a wood material");
    const TriangleMesh& mesh = *object.mesh;
    const WoodShader& shader = *material.wood;

    UvMaps maps;
    maps.width = options.width;
    maps.height = options.height;
    maps.finish = shader.finish();
    // The raster, 15 map channels and the writers' copies: ~136 bytes a texel.
    requireMemory(136.0 * options.width * options.height,
                  fmt::format("a set of {}x{} texture maps", options.width, options.height),
                  scene.file);
    maps.raster = rasterizeUv(mesh, options.width, options.height);
    clearMaps(maps);

    std::vector<TriangleFrame> frames(mesh.triangles.size());
    for (uint32_t t = 0; t < frames.size(); ++t) frames[t] = triangleFrame(mesh, t);
    const std::vector<Vec3> vertexNormals =
        mesh.normals.empty() ? computeVertexNormals(mesh) : mesh.normals;
    const BakeSurface surface{mesh, frames, vertexNormals, object.treeFromObject};
    const RigidTransform objectFromTree = object.treeFromObject.inverse();

    const int tilesX = (options.width + kTile - 1) / kTile;
    const int tilesY = (options.height + kTile - 1) / kTile;
    ProgressReporter progress(static_cast<long long>(tilesX) * tilesY, "Baking UV maps",
                              options.quiet);
    parallelTiles(size_t(tilesX) * tilesY, options.threads, [&](size_t tile) {
        const int x0 = static_cast<int>(tile % tilesX) * kTile;
        const int y0 = static_cast<int>(tile / tilesX) * kTile;
        const int x1 = std::min(options.width, x0 + kTile);
        const int y1 = std::min(options.height, y0 + kTile);
        const TileTexels texels = gatherTexels(surface, maps, x0, y0, x1, y1);
        std::vector<WoodSurfaceSample> samples(texels.points.size());
        WoodScratch scratch;
        shader.evaluateSurface(texels.points, texels.footprints, samples, scratch);
        storeTexels(texels, samples, objectFromTree, object.boardTint, maps);
        progress.advance();
    });
    progress.done();
    fillPastCharts(maps, options.padding);
    return maps;
}

}  // namespace nenrin
