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
    const size_t n = size_t(options.width) * options.height;
    // What texels no chart reaches hold: a flat normal, a fibre along +u, the finish's
    // roughness, so a host that samples them (mip-mapping, bilinear lookups) sees neutral
    // values, never a zero vector. The base colour is filled with the mean wood below.
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

    std::vector<TriangleFrame> frames(mesh.triangles.size());
    for (uint32_t t = 0; t < frames.size(); ++t) frames[t] = triangleFrame(mesh, t);
    std::vector<Vec3> vertexNormals =
        mesh.normals.empty() ? computeVertexNormals(mesh) : mesh.normals;

    const int tilesX = (options.width + kTile - 1) / kTile;
    const int tilesY = (options.height + kTile - 1) / kTile;
    ProgressReporter progress(static_cast<long long>(tilesX) * tilesY, "Baking UV maps",
                              options.quiet);
    const RigidTransform& treeFromObject = object.treeFromObject;
    parallelTiles(size_t(tilesX) * tilesY, options.threads, [&](size_t tile) {
        const int x0 = static_cast<int>(tile % tilesX) * kTile;
        const int y0 = static_cast<int>(tile / tilesX) * kTile;
        const int x1 = std::min(options.width, x0 + kTile);
        const int y1 = std::min(options.height, y0 + kTile);
        std::vector<size_t> texels;
        std::vector<Vec3> points, normals, tangents, bitangents;
        std::vector<SurfaceFootprint> footprints;
        for (int y = y0; y < y1; ++y) {
            for (int x = x0; x < x1; ++x) {
                size_t i = size_t(y) * options.width + x;
                int32_t t = maps.raster.triangle[i];
                if (t < 0 || !frames[t].valid) continue;
                const auto& tri = mesh.triangles[t];
                const auto& b = maps.raster.barycentric[i];
                Vec3 p = mesh.positions[tri[0]] * b[0] + mesh.positions[tri[1]] * b[1] +
                         mesh.positions[tri[2]] * b[2];
                Vec3 nrm = normalize(vertexNormals[tri[0]] * b[0] + vertexNormals[tri[1]] * b[1] +
                                     vertexNormals[tri[2]] * b[2]);
                if (lengthSquared(nrm) == 0) nrm = frames[t].normal;
                // Tangent along +u, bitangent along +v (mirrored charts flip it), both in the
                // surface: the frame normal maps and fibre maps are expressed in.
                Vec3 tangent = normalize(frames[t].dpdu - nrm * dot(nrm, frames[t].dpdu));
                Vec3 bitangent = cross(nrm, tangent);
                if (dot(bitangent, frames[t].dpdv) < 0) bitangent = -bitangent;
                texels.push_back(i);
                points.push_back(treeFromObject.point(p));
                normals.push_back(nrm);
                tangents.push_back(tangent);
                bitangents.push_back(bitangent);
                footprints.push_back({treeFromObject.vector(frames[t].dpdu / options.width),
                                      treeFromObject.vector(frames[t].dpdv / options.height), 0,
                                      treeFromObject.vector(nrm)});
            }
        }
        std::vector<WoodSurfaceSample> samples(points.size());
        WoodScratch scratch;
        shader.evaluateSurface(points, footprints, samples, scratch);
        const RigidTransform objectFromTree = treeFromObject.inverse();
        for (size_t k = 0; k < texels.size(); ++k) {
            size_t i = texels[k];
            const WoodSurfaceSample& s = samples[k];
            Rgb albedo = s.coverage > 0 || !(s.albedo == Rgb{}) ? s.albedo : kBarkAlbedo;
            maps.baseColour[3 * i] = float(albedo.r);
            maps.baseColour[3 * i + 1] = float(albedo.g);
            maps.baseColour[3 * i + 2] = float(albedo.b);
            maps.coverage[i] = 1;
            const Vec3 &n = normals[k], &t = tangents[k], &bt = bitangents[k];
            // The relief's mean slope over the texel: the host's mip-mapping does the rest.
            Vec3 g = objectFromTree.vector(s.meanReliefGradient);
            Vec3 bumped = normalize(n - (g - n * dot(g, n)));
            encodeUnit(&maps.normal[3 * i], {dot(bumped, t), dot(bumped, bt), dot(bumped, n)});
            Vec3 f = objectFromTree.vector(s.fibre);
            encodeUnit(&maps.fibre[3 * i], {dot(f, t), dot(f, bt), dot(f, n)});
            maps.growth[2 * i] = float(s.T);
            maps.growth[2 * i + 1] = float(s.knot);
        }
        progress.advance();
    });
    progress.done();

    // Gutter: every map grows by the same rings, so they stay aligned.
    std::vector<uint8_t> base = maps.raster.covered();
    auto pad = [&](std::vector<float>& pixels, int channels) {
        std::vector<uint8_t> covered = base;
        dilate(pixels, channels, maps.width, maps.height, covered, options.padding);
    };
    // Past the gutter the base colour is the mean wood (summed in a fixed order, so the bytes
    // do not depend on the threads), so far mip levels keep the wood's tone.
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
    return maps;
}

}  // namespace nenrin
