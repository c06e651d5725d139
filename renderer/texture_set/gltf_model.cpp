#include "renderer/texture_set/gltf_model.h"

#include <fmt/format.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "util/input_error.h"

namespace nenrin {

namespace {

constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr int kLinear = 9729, kLinearMipmapLinear = 9987, kRepeat = 10497;

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
    if (!mesh.uvs.empty()) v.uvs.resize(2 * v.count);
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
        if (mesh.uvs.empty()) continue;
        v.uvs[2 * i] = float(mesh.uvs[i][0]);
        v.uvs[2 * i + 1] = float(1 - mesh.uvs[i][1]);
    }
    if (!mesh.uvs.empty()) v.tangents = vertexTangents(mesh, normals);
    v.indices.reserve(3 * mesh.triangles.size());
    for (const auto& t : mesh.triangles) v.indices.insert(v.indices.end(), t.begin(), t.end());
    return v;
}

/// The node's mesh in buffer 0, as a mesh of its own placed by a node of the default scene.
void addMesh(tinygltf::Model& model, const GltfNode& node, int material) {
    const TriangleMesh& mesh = *node.mesh;
    const bool uvs = !mesh.uvs.empty();
    const GltfVertices v = gltfVertices(mesh);
    const size_t count = v.count;
    model.buffers.resize(1);
    std::vector<unsigned char>& data = model.buffers[0].data;
    auto addBufferView = [&](const auto& values, int target) {
        const size_t at = data.size();
        append(data, values.data(), values.size() * 4);
        return addView(model, at, values.size() * 4, target);
    };
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.attributes["POSITION"] =
        addAccessor(model, addBufferView(v.positions, kArrayBuffer), TINYGLTF_COMPONENT_TYPE_FLOAT,
                    TINYGLTF_TYPE_VEC3, count, v.lo, v.hi);
    prim.attributes["NORMAL"] =
        addAccessor(model, addBufferView(v.normals, kArrayBuffer), TINYGLTF_COMPONENT_TYPE_FLOAT,
                    TINYGLTF_TYPE_VEC3, count);
    if (uvs) {
        prim.attributes["TEXCOORD_0"] =
            addAccessor(model, addBufferView(v.uvs, kArrayBuffer), TINYGLTF_COMPONENT_TYPE_FLOAT,
                        TINYGLTF_TYPE_VEC2, count);
        prim.attributes["TANGENT"] =
            addAccessor(model, addBufferView(v.tangents, kArrayBuffer),
                        TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, count);
    }
    prim.indices =
        addAccessor(model, addBufferView(v.indices, kElementArrayBuffer),
                    TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, v.indices.size());
    prim.material = material;
    tinygltf::Mesh m;
    m.name = node.name;
    m.primitives.push_back(prim);
    model.meshes.push_back(m);
    tinygltf::Node n;
    n.name = node.name;
    n.mesh = int(model.meshes.size()) - 1;
    model.nodes.push_back(n);
    model.scenes[0].nodes.push_back(int(model.nodes.size()) - 1);
}

void declareExtension(tinygltf::Model& model, const std::string& name) {
    if (std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), name) ==
        model.extensionsUsed.end())
        model.extensionsUsed.push_back(name);
}

/// The node's material: a texture set (textures i = images i, sampler 0), its coat as
/// KHR_materials_clearcoat and fibre highlight as KHR_materials_anisotropy; or a colour.
int addMaterial(tinygltf::Model& model, const GltfNode& node) {
    tinygltf::Material material;
    material.name = node.materialName;
    material.pbrMetallicRoughness.metallicFactor = 0;
    if (!node.textured()) {
        material.pbrMetallicRoughness.baseColorFactor = {node.colour.r, node.colour.g,
                                                         node.colour.b, 1};
        material.pbrMetallicRoughness.roughnessFactor = 0.6;
        model.materials.push_back(material);
        return int(model.materials.size()) - 1;
    }
    const PbrFinish& p = node.finish;
    material.pbrMetallicRoughness.baseColorTexture.index = node.images[0];
    material.pbrMetallicRoughness.roughnessFactor = 1;
    material.pbrMetallicRoughness.metallicRoughnessTexture.index = node.images[1];
    material.normalTexture.index = node.images[2];
    if (p.coatWeight > 0) {
        tinygltf::Value::Object coat;
        coat["clearcoatFactor"] = number(p.coatWeight);
        coat["clearcoatRoughnessFactor"] = number(p.coatRoughness);
        material.extensions["KHR_materials_clearcoat"] = tinygltf::Value(coat);
        declareExtension(model, "KHR_materials_clearcoat");
    }
    if (p.anisotropy > 0 && node.images[3] >= 0) {
        tinygltf::Value::Object aniso;
        aniso["anisotropyStrength"] = number(p.anisotropy);
        aniso["anisotropyTexture"] = textureInfo(node.images[3]);
        material.extensions["KHR_materials_anisotropy"] = tinygltf::Value(aniso);
        declareExtension(model, "KHR_materials_anisotropy");
    }
    model.materials.push_back(material);
    return int(model.materials.size()) - 1;
}

/// The model without images' data: the meshes in buffer 0, materials, and one texture per
/// image (texture i shows image i).
tinygltf::Model buildModel(const std::vector<GltfNode>& nodes, size_t images,
                           const std::string& generator) {
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = generator;
    model.scenes.resize(1);
    model.defaultScene = 0;
    if (images > 0) {
        tinygltf::Sampler sampler;
        sampler.magFilter = kLinear;
        sampler.minFilter = kLinearMipmapLinear;
        sampler.wrapS = sampler.wrapT = kRepeat;
        model.samplers.push_back(sampler);
    }
    for (size_t i = 0; i < images; ++i) {
        tinygltf::Texture texture;
        texture.sampler = 0;
        texture.source = int(i);
        model.textures.push_back(texture);
    }
    for (const GltfNode& node : nodes) addMesh(model, node, addMaterial(model, node));
    return model;
}

}  // namespace

void writeGltfModel(const std::vector<GltfNode>& nodes, const std::vector<GltfImage>& images,
                    const std::string& stem, const std::string& generator, FolderOutputs& out) {
    tinygltf::TinyGLTF writer;
    tinygltf::Model model = buildModel(nodes, images.size(), generator);
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
        for (const GltfImage& png : images) {
            tinygltf::Image image;
            image.uri = png.uri;
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
    // .glb: one file, the images in buffer views of the binary chunk after the meshes.
    std::vector<unsigned char>& data = model.buffers[0].data;
    for (const GltfImage& png : images) {
        const size_t at = data.size();
        append(data, png.png.data(), png.png.size());
        tinygltf::Image image;
        image.mimeType = "image/png";
        image.bufferView = addView(model, at, png.png.size(), 0);
        model.images.push_back(image);
    }
    const std::string& glbPath = out.add(stem + ".glb");
    std::ofstream glb(glbPath, std::ios::binary);
    if (!writer.WriteGltfSceneToStream(&model, glb, false, true) || !glb.flush())
        throw InputError(out.last(), "output", "cannot write it (disk full?)");
}

}  // namespace nenrin
