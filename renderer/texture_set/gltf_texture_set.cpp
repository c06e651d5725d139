#include "renderer/texture_set/gltf_texture_set.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "grain/cielab.h"
#include "renderer/png_file.h"
#include "renderer/texture_set/folder_outputs.h"
#include "renderer/texture_set/gltf_model.h"
#include "renderer/texture_set/texture_set_files.h"
#include "util/input_error.h"
#include "util/input_file.h"

namespace nenrin {

namespace {

uint8_t byteOf(double v) {
    return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255));
}

/// The four PNG textures, 8-bit RGB, row 0 at the top (glTF's uv (0, 0)).
struct Textures {
    std::vector<uint8_t> baseColour, metallicRoughness, normal, anisotropy;
};

Textures encodeTextures(const UvMaps& maps) {
    const size_t n = size_t(maps.width) * maps.height;
    Textures t;
    t.baseColour.resize(3 * n);
    t.metallicRoughness.resize(3 * n);
    t.normal.resize(3 * n);
    t.anisotropy.resize(3 * n);
    for (size_t i = 0; i < n; ++i) {
        for (int c = 0; c < 3; ++c) {
            t.baseColour[3 * i + c] = byteOf(srgbFromLinear(maps.baseColour[3 * i + c]));
            t.normal[3 * i + c] = byteOf(maps.normal[3 * i + c]);
        }
        // R is occlusion in packed ORM textures: 1 (none), so a host that reads it sees none.
        t.metallicRoughness[3 * i] = 255;
        t.metallicRoughness[3 * i + 1] = byteOf(maps.roughness[i]);
        t.metallicRoughness[3 * i + 2] = 0;
        // The fibre's part in the surface; the lobe stretches across it (the fibre turned by
        // 90 degrees about the normal), as strongly as the fibre lies in the surface: on end
        // grain it points out of the surface and the lobe is round.
        double fx = 2 * maps.fibre[3 * i] - 1, fy = 2 * maps.fibre[3 * i + 1] - 1;
        // A fibre is a line (f and -f are one fibre) and so is glTF's lobe direction: of the
        // two, the one that rises out of the surface is written, so that a reader can tell
        // which way the fibre dives (textured materials of nenrin take it out of the surface).
        if (maps.fibre[3 * i + 2] < 0.5) {
            fx = -fx;
            fy = -fy;
        }
        double inPlane = std::min(1.0, std::hypot(fx, fy));
        double ax = 1, ay = 0;
        if (inPlane > 1e-6) {
            ax = -fy / std::hypot(fx, fy);
            ay = fx / std::hypot(fx, fy);
        }
        t.anisotropy[3 * i] = byteOf(0.5 * ax + 0.5);
        t.anisotropy[3 * i + 1] = byteOf(0.5 * ay + 0.5);
        // Strength 1 for a fibre in the surface, 0 for one through it, linear in the angle
        // (8 bits of cos(angle) would resolve the small angles of side grain in 5 degree steps).
        t.anisotropy[3 * i + 2] = byteOf(1 - std::acos(inPlane) / (0.5 * std::numbers::pi));
    }
    return t;
}

/// Reads back a PNG just written, for the GLB's embedded images.
std::vector<unsigned char> fileBytes(const std::string& path, const std::string& finalPath) {
    std::string bytes = readInputFile(path, uintmax_t(1) << 32, "a PNG just written");
    if (bytes.empty()) throw InputError(finalPath, "output", "the PNG is empty (disk full?)");
    return {bytes.begin(), bytes.end()};
}

}  // namespace

GltfTextureSet writeGltfTextureSet(const UvMaps& maps, const SceneObject& object,
                                   const std::string& folder,
                                   const std::map<std::string, std::string>& metadata) {
    FolderOutputs out(folder, "the glTF files");
    const std::string stem = textureSetStem(object.name);

    const Textures textures = encodeTextures(maps);
    struct Png {
        const char* file;
        const std::vector<uint8_t>* rgb;
        PngValues values;
    };
    std::vector<Png> pngs = {
        {"basecolor.png", &textures.baseColour, PngValues::SrgbColour},
        {"metallic-roughness.png", &textures.metallicRoughness, PngValues::Data},
        {"normal.png", &textures.normal, PngValues::Data}};
    GltfTextureSet set;
    set.finish = pbrFinish(maps.finish);
    // Without a fibre highlight (bare wood) the lobe is round: no anisotropy texture.
    if (set.finish.anisotropy > 0)
        pngs.push_back({"anisotropy.png", &textures.anisotropy, PngValues::Data});
    GltfNode node;
    node.name = object.name;
    node.mesh = object.mesh.get();
    node.materialName = stem;
    node.finish = set.finish;
    for (size_t i = 0; i < pngs.size(); ++i) {
        const Png& png = pngs[i];
        const std::string& path = out.add(png.file);
        writePng8(out.last(), path, maps.width, maps.height, *png.rgb, metadata, png.values);
        set.images.push_back({png.file, fileBytes(path, out.last())});
        node.images[i] = int(i);
    }
    const std::string generator =
        "nenrin " + (metadata.count("version") ? metadata.at("version") : "");
    writeGltfModel({node}, set.images, stem, generator, out);
    set.written = out.commit();
    return set;
}

}  // namespace nenrin
