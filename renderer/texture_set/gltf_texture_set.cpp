#include "renderer/texture_set/gltf_texture_set.h"

#include <fmt/format.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "grain/cielab.h"
#include "renderer/png_file.h"
#include "renderer/texture_set/folder_outputs.h"
#include "renderer/texture_set/pbr_finish.h"
#include "renderer/texture_set/texture_set_files.h"
#include "util/input_error.h"
#include "util/input_file.h"

namespace nenrin {

namespace {

constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr int kLinear = 9729, kLinearMipmapLinear = 9987, kRepeat = 10497;

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
        double inPlane = std::min(1.0, std::hypot(fx, fy));
        double ax = 1, ay = 0;
        if (inPlane > 1e-6) {
            ax = -fy / std::hypot(fx, fy);
            ay = fx / std::hypot(fx, fy);
        }
        t.anisotropy[3 * i] = byteOf(0.5 * ax + 0.5);
        t.anisotropy[3 * i + 1] = byteOf(0.5 * ay + 0.5);
        t.anisotropy[3 * i + 2] = byteOf(inPlane);
    }
    return t;
}

void append(std::vector<unsigned char>& data, const void* bytes, size_t size) {
    const auto* b = static_cast<const unsigned char*>(bytes);
    data.insert(data.end(), b, b + size);
    while (data.size() % 4) data.push_back(0);  // every view 4-byte aligned
}

int addView(tinygltf::Model& model, size_t offset, size_t length, int target) {
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = offset;
    view.byteLength = length;
    view.target = target;
    model.bufferViews.push_back(view);
    return int(model.bufferViews.size()) - 1;
}

int addAccessor(tinygltf::Model& model, int view, int componentType, int type, size_t count,
                std::vector<double> min = {}, std::vector<double> max = {}) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.componentType = componentType;
    a.type = type;
    a.count = count;
    a.minValues = std::move(min);
    a.maxValues = std::move(max);
    model.accessors.push_back(a);
    return int(model.accessors.size()) - 1;
}

tinygltf::Value number(double v) { return tinygltf::Value(v); }

tinygltf::Value textureInfo(int index) {
    tinygltf::Value::Object o;
    o["index"] = tinygltf::Value(index);
    return tinygltf::Value(o);
}

/// Per vertex: the tangent along +u (the sum of its triangles' dP/du, made perpendicular to the
/// normal) and in w the sign that makes cross(normal, tangent) * w point along +v (image up), the
/// frame the maps were baked in. Written so that hosts need not generate one (MikkTSpace would
/// agree on a well-shaped mesh, but not everywhere).
std::vector<float> vertexTangents(const TriangleMesh& mesh, const std::vector<Vec3>& normals) {
    std::vector<Vec3> du(mesh.positions.size()), dv(mesh.positions.size());
    for (const auto& tri : mesh.triangles) {
        Vec3 p0 = mesh.positions[tri[0]], p1 = mesh.positions[tri[1]], p2 = mesh.positions[tri[2]];
        auto uv0 = mesh.uvs[tri[0]], uv1 = mesh.uvs[tri[1]], uv2 = mesh.uvs[tri[2]];
        double du1 = uv1[0] - uv0[0], dv1 = uv1[1] - uv0[1];
        double du2 = uv2[0] - uv0[0], dv2 = uv2[1] - uv0[1];
        double det = du1 * dv2 - du2 * dv1;
        if (std::abs(det) < 1e-30) continue;
        Vec3 e1 = p1 - p0, e2 = p2 - p0;
        Vec3 dpdu = (e1 * dv2 - e2 * dv1) / det, dpdv = (e2 * du1 - e1 * du2) / det;
        // Weighted by the triangle's area in uv, so slivers count little.
        double w = std::abs(det);
        for (uint32_t v : tri) {
            du[v] = du[v] + normalize(dpdu) * w;
            dv[v] = dv[v] + normalize(dpdv) * w;
        }
    }
    std::vector<float> out(4 * mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        const Vec3 n =
            normalize(Vec3{float(normals[v].x), float(normals[v].y), float(normals[v].z)});
        Vec3 t = du[v] - n * dot(n, du[v]);
        // No uv area here: any direction in the surface.
        t = lengthSquared(t) < 1e-20 ? anyPerpendicular(n) : normalize(t);
        out[4 * v] = float(t.x);
        out[4 * v + 1] = float(t.y);
        out[4 * v + 2] = float(t.z);
        out[4 * v + 3] = dot(cross(n, t), dv[v]) < 0 ? -1.f : 1.f;
    }
    return out;
}

/// A mesh's vertex data as glTF wants it: float positions (with their float bounds), unit
/// normals, uvs with v running down, tangents, and the triangle indices.
struct GltfVertices {
    size_t count = 0;
    std::vector<float> positions, normals, uvs, tangents;
    std::vector<double> lo, hi;
    std::vector<uint32_t> indices;
};

GltfVertices gltfVertices(const TriangleMesh& mesh) {
    const std::vector<Vec3> normals =
        mesh.normals.empty() ? computeVertexNormals(mesh) : mesh.normals;
    GltfVertices v;
    v.count = mesh.positions.size();
    v.positions.resize(3 * v.count);
    v.normals.resize(3 * v.count);
    v.uvs.resize(2 * v.count);
    v.lo = {1e300, 1e300, 1e300};
    v.hi = {-1e300, -1e300, -1e300};
    for (size_t i = 0; i < v.count; ++i) {
        const double p[3] = {mesh.positions[i].x, mesh.positions[i].y, mesh.positions[i].z};
        const double q[3] = {normals[i].x, normals[i].y, normals[i].z};
        for (int c = 0; c < 3; ++c) {
            v.positions[3 * i + c] = float(p[c]);
            // Stored as float, the bounds are the float values (the validator checks them).
            v.lo[c] = std::min(v.lo[c], double(v.positions[3 * i + c]));
            v.hi[c] = std::max(v.hi[c], double(v.positions[3 * i + c]));
        }
        Vec3 nrm = normalize(Vec3{float(q[0]), float(q[1]), float(q[2])});
        v.normals[3 * i] = float(nrm.x);
        v.normals[3 * i + 1] = float(nrm.y);
        v.normals[3 * i + 2] = float(nrm.z);
        // glTF's v runs down the image, OBJ's up.
        v.uvs[2 * i] = float(mesh.uvs[i][0]);
        v.uvs[2 * i + 1] = float(1 - mesh.uvs[i][1]);
    }
    v.tangents = vertexTangents(mesh, normals);
    v.indices.reserve(3 * mesh.triangles.size());
    for (const auto& t : mesh.triangles) v.indices.insert(v.indices.end(), t.begin(), t.end());
    return v;
}

/// The mesh in buffer 0, as mesh 0 of node 0 of the default scene, with material 0.
void addMesh(tinygltf::Model& model, const SceneObject& object) {
    const GltfVertices v = gltfVertices(*object.mesh);
    const size_t count = v.count;
    model.buffers.resize(1);
    std::vector<unsigned char>& data = model.buffers[0].data;
    auto addBufferView = [&](const auto& values, int target) {
        const size_t at = data.size();
        append(data, values.data(), values.size() * 4);
        return addView(model, at, values.size() * 4, target);
    };
    const int posView = addBufferView(v.positions, kArrayBuffer);
    const int nrmView = addBufferView(v.normals, kArrayBuffer);
    const int uvView = addBufferView(v.uvs, kArrayBuffer);
    const int tanView = addBufferView(v.tangents, kArrayBuffer);
    const int idxView = addBufferView(v.indices, kElementArrayBuffer);

    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.attributes["POSITION"] = addAccessor(model, posView, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                              TINYGLTF_TYPE_VEC3, count, v.lo, v.hi);
    prim.attributes["NORMAL"] =
        addAccessor(model, nrmView, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, count);
    prim.attributes["TEXCOORD_0"] =
        addAccessor(model, uvView, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, count);
    prim.attributes["TANGENT"] =
        addAccessor(model, tanView, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, count);
    prim.indices = addAccessor(model, idxView, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                               TINYGLTF_TYPE_SCALAR, v.indices.size());
    prim.material = 0;
    tinygltf::Mesh m;
    m.name = object.name;
    m.primitives.push_back(prim);
    model.meshes.push_back(m);
    tinygltf::Node node;
    node.name = object.name;
    node.mesh = 0;
    model.nodes.push_back(node);
    tinygltf::Scene scene;
    scene.nodes = {0};
    model.scenes.push_back(scene);
    model.defaultScene = 0;
}

/// The sampler, the textures of images 0..3 and the material over them: the finish's coat
/// as KHR_materials_clearcoat, its fibre highlight as KHR_materials_anisotropy.
void addMaterial(tinygltf::Model& model, const UvMaps& maps, const SceneObject& object) {
    tinygltf::Sampler sampler;
    sampler.magFilter = kLinear;
    sampler.minFilter = kLinearMipmapLinear;
    sampler.wrapS = sampler.wrapT = kRepeat;
    model.samplers.push_back(sampler);
    const PbrFinish p = pbrFinish(maps.finish);
    for (int i = 0; i < (p.anisotropy > 0 ? 4 : 3); ++i) {
        tinygltf::Texture texture;
        texture.sampler = 0;
        texture.source = i;
        model.textures.push_back(texture);
    }

    tinygltf::Material material;
    material.name = textureSetStem(object.name);
    material.pbrMetallicRoughness.baseColorTexture.index = 0;
    material.pbrMetallicRoughness.metallicFactor = 0;
    material.pbrMetallicRoughness.roughnessFactor = 1;
    material.pbrMetallicRoughness.metallicRoughnessTexture.index = 1;
    material.normalTexture.index = 2;
    if (p.coatWeight > 0) {
        tinygltf::Value::Object coat;
        coat["clearcoatFactor"] = number(p.coatWeight);
        coat["clearcoatRoughnessFactor"] = number(p.coatRoughness);
        material.extensions["KHR_materials_clearcoat"] = tinygltf::Value(coat);
        model.extensionsUsed.push_back("KHR_materials_clearcoat");
    }
    if (p.anisotropy > 0) {
        tinygltf::Value::Object aniso;
        aniso["anisotropyStrength"] = number(p.anisotropy);
        aniso["anisotropyTexture"] = textureInfo(3);
        material.extensions["KHR_materials_anisotropy"] = tinygltf::Value(aniso);
        model.extensionsUsed.push_back("KHR_materials_anisotropy");
    }
    model.materials.push_back(material);
}

/// The model without images' data: the mesh in buffer 0, the material, textures pointing at
/// images 0..3 (base colour, metallic-roughness, normal and, with a fibre highlight,
/// anisotropy).
tinygltf::Model buildModel(const UvMaps& maps, const SceneObject& object,
                           const std::map<std::string, std::string>& metadata) {
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "nenrin " + (metadata.count("version") ? metadata.at("version") : "");
    addMesh(model, object);
    addMaterial(model, maps, object);
    return model;
}

/// Reads back a PNG just written, for the GLB's embedded images.
std::vector<unsigned char> fileBytes(const std::string& path, const std::string& finalPath) {
    std::string bytes = readInputFile(path, uintmax_t(1) << 32, "a PNG just written");
    if (bytes.empty()) throw InputError(finalPath, "output", "the PNG is empty (disk full?)");
    return {bytes.begin(), bytes.end()};
}

}  // namespace

std::vector<std::string> writeGltfTextureSet(const UvMaps& maps, const SceneObject& object,
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
    // Without a fibre highlight (bare wood) the lobe is round: no anisotropy texture.
    if (pbrFinish(maps.finish).anisotropy > 0)
        pngs.push_back({"anisotropy.png", &textures.anisotropy, PngValues::Data});
    std::vector<std::string> pngTemporary;
    for (const Png& png : pngs) {
        const std::string& path = out.add(png.file);
        writePng8(out.last(), path, maps.width, maps.height, *png.rgb, metadata, png.values);
        pngTemporary.push_back(path);
    }

    tinygltf::TinyGLTF writer;
    tinygltf::Model model = buildModel(maps, object, metadata);
    const std::vector<unsigned char>& mesh = model.buffers[0].data;
    // .gltf + .bin: the images by name, the buffer as its own file. tinygltf's stream writer
    // would embed the buffer as base64 (and its file writer names and writes the .bin itself,
    // outside the temporary names): the JSON is serialised without buffers, and the one buffer
    // entry, pointing at the .bin, added here.
    {
        const std::string& binPath = out.add(stem + ".bin");
        std::ofstream bin(binPath, std::ios::binary);
        bin.write(reinterpret_cast<const char*>(mesh.data()), std::streamsize(mesh.size()));
        bin.flush();
        if (!bin) throw InputError(out.last(), "output", "cannot write it (disk full?)");
    }
    {
        tinygltf::Model named = model;
        named.buffers.clear();
        for (const Png& png : pngs) {
            tinygltf::Image image;
            image.uri = png.file;
            named.images.push_back(image);
        }
        const std::string& gltfPath = out.add(stem + ".gltf");
        std::ostringstream json;
        if (!writer.WriteGltfSceneToStream(&named, json, true, false))
            throw InputError(out.last(), "output", "tinygltf cannot serialise the model");
        nlohmann::json doc = nlohmann::json::parse(json.str());
        doc["buffers"] =
            nlohmann::json::array({{{"uri", stem + ".bin"}, {"byteLength", mesh.size()}}});
        std::ofstream file(gltfPath);
        file << doc.dump(2) << "\n";
        file.flush();
        if (!file) throw InputError(out.last(), "output", "cannot write it (disk full?)");
    }
    // .glb: one file, the images in buffer views of the binary chunk after the mesh.
    {
        std::vector<unsigned char>& data = model.buffers[0].data;
        for (size_t i = 0; i < pngs.size(); ++i) {
            std::vector<unsigned char> png = fileBytes(pngTemporary[i], pngs[i].file);
            size_t at = data.size();
            append(data, png.data(), png.size());
            tinygltf::Image image;
            image.mimeType = "image/png";
            image.bufferView = addView(model, at, png.size(), 0);
            model.images.push_back(image);
        }
        const std::string& glbPath = out.add(stem + ".glb");
        std::ofstream glb(glbPath, std::ios::binary);
        if (!writer.WriteGltfSceneToStream(&model, glb, false, true) || !glb.flush())
            throw InputError(out.last(), "output", "cannot write it (disk full?)");
    }
    return out.commit();
}

}  // namespace nenrin
