#include "renderer/geometry/gltf_mesh.h"

#include <fmt/format.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>

#include "util/atomic_output.h"
#include "util/input_error.h"
#include "util/input_file.h"

namespace nenrin {

namespace {

constexpr uintmax_t kMaxGltfFileBytes = uintmax_t(1) << 30;

using Matrix = std::array<double, 16>;  // column-major, as glTF stores it

Matrix identity() { return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }

Matrix multiply(const Matrix& a, const Matrix& b) {
    Matrix m{};
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            for (int k = 0; k < 4; ++k) m[c * 4 + r] += a[k * 4 + r] * b[c * 4 + k];
    return m;
}

Vec3 transformPoint(const Matrix& m, const Vec3& p) {
    return {m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12],
            m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13],
            m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14]};
}

/// The upper 3x3's cofactor matrix applied to n: the normal transform (inverse transpose up to
/// a positive factor times the determinant's sign, which normalisation and the caller handle).
Vec3 transformNormal(const Matrix& m, const Vec3& n) {
    Vec3 c0{m[0], m[1], m[2]}, c1{m[4], m[5], m[6]}, c2{m[8], m[9], m[10]};
    Vec3 r0 = cross(c1, c2), r1 = cross(c2, c0), r2 = cross(c0, c1);
    Vec3 out = r0 * n.x + r1 * n.y + r2 * n.z;
    double det = dot(c0, r0);
    return det < 0 ? -out : out;
}

double determinant(const Matrix& m) {
    return dot(Vec3{m[0], m[1], m[2]}, cross(Vec3{m[4], m[5], m[6]}, Vec3{m[8], m[9], m[10]}));
}

Matrix localMatrix(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) {
        Matrix m;
        std::copy(node.matrix.begin(), node.matrix.end(), m.begin());
        return m;
    }
    Matrix t = identity(), r = identity(), s = identity();
    if (node.translation.size() == 3) {
        t[12] = node.translation[0];
        t[13] = node.translation[1];
        t[14] = node.translation[2];
    }
    if (node.rotation.size() == 4) {
        double x = node.rotation[0], y = node.rotation[1], z = node.rotation[2],
               w = node.rotation[3];
        r = {1 - 2 * (y * y + z * z),
             2 * (x * y + z * w),
             2 * (x * z - y * w),
             0,
             2 * (x * y - z * w),
             1 - 2 * (x * x + z * z),
             2 * (y * z + x * w),
             0,
             2 * (x * z + y * w),
             2 * (y * z - x * w),
             1 - 2 * (x * x + y * y),
             0,
             0,
             0,
             0,
             1};
    }
    if (node.scale.size() == 3) {
        s[0] = node.scale[0];
        s[5] = node.scale[1];
        s[10] = node.scale[2];
    }
    return multiply(t, multiply(r, s));
}

class Reader {
public:
    Reader(const std::string& path, const tinygltf::Model& model) : path_(path), model_(model) {}

    /// The accessor's elements as doubles, `components` per element (normalised integers are
    /// mapped to [0, 1] as glTF defines).
    std::vector<double> read(int index, int type, const std::string& where) const {
        if (index < 0 || index >= int(model_.accessors.size()))
            throw InputError(path_, where, fmt::format("accessor {} does not exist", index));
        const tinygltf::Accessor& a = model_.accessors[index];
        const std::string at = fmt::format("{}, accessor {}", where, index);
        if (a.sparse.isSparse) throw InputError(path_, at, "sparse accessors are not supported");
        if (a.type != type)
            throw InputError(path_, at,
                             fmt::format("expected {} components per element",
                                         tinygltf::GetNumComponentsInType(type)));
        if (a.bufferView < 0 || a.bufferView >= int(model_.bufferViews.size()))
            throw InputError(path_, at, "expected a buffer view with the data");
        const tinygltf::BufferView& view = model_.bufferViews[a.bufferView];
        if (view.buffer < 0 || view.buffer >= int(model_.buffers.size()))
            throw InputError(path_, at, "its buffer view names no buffer");
        const std::vector<unsigned char>& data = model_.buffers[view.buffer].data;
        const int components = tinygltf::GetNumComponentsInType(type);
        const int size = tinygltf::GetComponentSizeInBytes(a.componentType);
        if (size <= 0) throw InputError(path_, at, "unknown component type");
        const size_t element = size_t(size) * components;
        const size_t stride = view.byteStride ? view.byteStride : element;
        // Every byte read must lie inside the view, and the view inside the buffer.
        const size_t viewEnd = view.byteOffset + view.byteLength;
        if (viewEnd < view.byteOffset || viewEnd > data.size())
            throw InputError(path_, at,
                             fmt::format("its buffer view ends at byte {}, past the buffer's {}",
                                         viewEnd, data.size()));
        if (a.count > 0 && (a.byteOffset > view.byteLength ||
                            (a.count - 1) > (view.byteLength - a.byteOffset) / stride ||
                            a.byteOffset + (a.count - 1) * stride + element > view.byteLength))
            throw InputError(path_, at,
                             fmt::format("{} elements do not fit in its buffer view of {} bytes",
                                         a.count, view.byteLength));
        std::vector<double> out(a.count * components);
        const unsigned char* base = data.data() + view.byteOffset + a.byteOffset;
        for (size_t i = 0; i < a.count; ++i) {
            const unsigned char* e = base + i * stride;
            for (int c = 0; c < components; ++c) {
                const unsigned char* v = e + size_t(c) * size;
                double x = 0;
                switch (a.componentType) {
                    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
                        float f;
                        std::memcpy(&f, v, 4);
                        x = f;
                        break;
                    }
                    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                        x = a.normalized ? *v / 255.0 : *v;
                        break;
                    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                        uint16_t u;
                        std::memcpy(&u, v, 2);
                        x = a.normalized ? u / 65535.0 : u;
                        break;
                    }
                    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
                        uint32_t u;
                        std::memcpy(&u, v, 4);
                        x = u;
                        break;
                    }
                    default:
                        throw InputError(path_, at,
                                         "expected float, unsigned byte, short or int components");
                }
                if (!std::isfinite(x))
                    throw InputError(path_, at,
                                     fmt::format("element {} is not a finite number", i));
                out[i * components + c] = x;
            }
        }
        return out;
    }

private:
    const std::string& path_;
    const tinygltf::Model& model_;
};

bool noImageDecoding(tinygltf::Image*, const int, std::string*, std::string*, int, int,
                     const unsigned char*, int, void*) {
    return true;
}

/// Buffers are read through nenrin's input rules (no devices, no folders, a size limit);
/// paths are taken as written.
bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                   void*) {
    try {
        std::string bytes = readInputFile(path, kMaxGltfFileBytes, "a glTF buffer");
        out->assign(bytes.begin(), bytes.end());
        return true;
    } catch (const InputError& e) {
        *err += e.what();
        return false;
    }
}
std::string expandNothing(const std::string& path, void*) { return path; }
/// A name the system refuses (too long, a bad component) is a file that is not there, not a throw.
bool fileExists(const std::string& path, void*) {
    std::error_code ec;
    return std::filesystem::exists(path, ec);
}
bool refuseWriting(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    *err = "nenrin does not write while reading a glTF";
    return false;
}

}  // namespace

bool isGltfPath(const std::string& path) {
    const std::string ext = lowerExtension(path);
    return ext == ".gltf" || ext == ".glb";
}

namespace {

/// The file as tinygltf reads it (buffers through nenrin's input rules, images not decoded).
tinygltf::Model readModel(const std::string& path) {
    const std::string bytes = readInputFile(path, kMaxGltfFileBytes, "a glTF file");
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(noImageDecoding, nullptr);
    loader.SetFsCallbacks({fileExists, expandNothing, readWholeFile, refuseWriting, nullptr});
    tinygltf::Model model;
    std::string err, warn;
    const std::string dir = std::filesystem::absolute(path).parent_path().string();
    const bool binary = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
    bool ok =
        binary ? loader.LoadBinaryFromMemory(&model, &err, &warn,
                                             reinterpret_cast<const unsigned char*>(bytes.data()),
                                             static_cast<unsigned int>(bytes.size()), dir)
               : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(),
                                            static_cast<unsigned int>(bytes.size()), dir);
    if (!ok)
        throw InputError(
            path, "",
            "tinygltf cannot read the file: " + oneLine(err.empty() ? "unknown error" : err));
    return model;
}

/// Which meshes, with which transforms: the default scene's node trees (every mesh once,
/// untransformed, in a file without scenes).
std::vector<std::pair<int, Matrix>> meshInstances(const tinygltf::Model& model,
                                                  const std::string& path,
                                                  const std::string& nodeName) {
    std::vector<std::pair<int, Matrix>> instances;
    bool named = false;  // a node of that name was met
    auto visit = [&](auto&& self, int node, const Matrix& parent, int level, bool inside) -> void {
        if (node < 0 || node >= int(model.nodes.size()))
            throw InputError(path, fmt::format("node {}", node), "the node does not exist");
        if (level > 64)
            throw InputError(path, fmt::format("node {}", node),
                             "nodes nest deeper than 64 levels (a cycle?)");
        const tinygltf::Node& n = model.nodes[node];
        Matrix world = multiply(parent, localMatrix(n));
        if (!nodeName.empty() && n.name == nodeName) inside = named = true;
        if (n.mesh >= 0 && inside) instances.push_back({n.mesh, world});
        for (int child : n.children) self(self, child, world, level + 1, inside);
    };
    int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : (model.scenes.empty() ? -1 : 0);
    if (sceneIndex >= int(model.scenes.size()))
        throw InputError(path, "scene", fmt::format("scene {} does not exist", sceneIndex));
    if (sceneIndex >= 0) {
        for (int root : model.scenes[sceneIndex].nodes)
            visit(visit, root, identity(), 0, nodeName.empty());
    } else if (nodeName.empty()) {
        for (int m = 0; m < int(model.meshes.size()); ++m) instances.push_back({m, identity()});
    }
    if (!nodeName.empty() && !named)
        throw InputError(path, "", fmt::format("no node named \"{}\" in the scene", nodeName));
    return instances;
}

/// A primitive's triangle indices: its index accessor's, or 0, 1, 2, ... without one.
std::vector<double> primitiveIndices(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                     Reader& reader, size_t count, const std::string& path,
                                     const std::string& where) {
    std::vector<double> idx;
    if (prim.indices >= 0) {
        // glTF indices are unsigned integers; a float accessor (found by fuzzing: an
        // index of -2.9e36) is refused here, and every value is range-checked later.
        if (prim.indices < int(model.accessors.size())) {
            const int type = model.accessors[prim.indices].componentType;
            if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
                throw InputError(path, fmt::format("{}, indices, accessor {}", where, prim.indices),
                                 "expected unsigned byte, short or int indices");
        }
        idx = reader.read(prim.indices, TINYGLTF_TYPE_SCALAR, where + ", indices");
    } else {
        idx.resize(count);
        for (size_t i = 0; i < count; ++i) idx[i] = double(i);
    }
    if (idx.size() % 3 != 0)
        throw InputError(path, where,
                         fmt::format("{} indices: expected a multiple of 3", idx.size()));
    return idx;
}

/// Which attributes the primitives had, for the all-or-none checks.
struct AttributeCounts {
    int primitives = 0, withNormals = 0, withUvs = 0;
};

/// Appends one triangle primitive, transformed into the file's world space.
void appendPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                     const Matrix& world, Reader& reader, const std::string& path,
                     const std::string& where, TriangleMesh& mesh, AttributeCounts& counts) {
    auto attribute = [&](const char* name) {
        auto it = prim.attributes.find(name);
        return it == prim.attributes.end() ? -1 : it->second;
    };
    if (attribute("POSITION") < 0) throw InputError(path, where, "expected a POSITION attribute");
    std::vector<double> pos =
        reader.read(attribute("POSITION"), TINYGLTF_TYPE_VEC3, where + ", POSITION");
    const size_t count = pos.size() / 3;
    std::vector<double> nrm, uv;
    if (attribute("NORMAL") >= 0)
        nrm = reader.read(attribute("NORMAL"), TINYGLTF_TYPE_VEC3, where + ", NORMAL");
    if (attribute("TEXCOORD_0") >= 0)
        uv = reader.read(attribute("TEXCOORD_0"), TINYGLTF_TYPE_VEC2, where + ", TEXCOORD_0");
    if ((!nrm.empty() && nrm.size() != pos.size()) || (!uv.empty() && uv.size() / 2 != count))
        throw InputError(path, where,
                         "expected NORMAL and TEXCOORD_0 with as many elements as POSITION");
    const std::vector<double> idx = primitiveIndices(model, prim, reader, count, path, where);
    ++counts.primitives;
    counts.withNormals += !nrm.empty();
    counts.withUvs += !uv.empty();
    const uint32_t first = static_cast<uint32_t>(mesh.positions.size());
    for (size_t i = 0; i < count; ++i) {
        mesh.positions.push_back(
            transformPoint(world, {pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]}));
        if (!nrm.empty()) {
            Vec3 n = transformNormal(world, {nrm[3 * i], nrm[3 * i + 1], nrm[3 * i + 2]});
            mesh.normals.push_back(lengthSquared(n) > 0 ? normalize(n) : Vec3{0, 0, 1});
        }
        if (!uv.empty()) mesh.uvs.push_back({uv[2 * i], 1 - uv[2 * i + 1]});
    }
    const bool mirrored = determinant(world) < 0;
    for (size_t t = 0; t < idx.size(); t += 3) {
        std::array<uint32_t, 3> tri;
        for (int c = 0; c < 3; ++c) {
            if (!(idx[t + c] >= 0 && idx[t + c] < double(count)))
                throw InputError(path, where,
                                 fmt::format("index {} (triangle {}) is past the {} vertices",
                                             idx[t + c], t / 3, count));
            tri[c] = first + static_cast<uint32_t>(idx[t + c]);
        }
        if (mirrored) std::swap(tri[1], tri[2]);
        mesh.triangles.push_back(tri);
    }
    if (mesh.positions.size() > (size_t(1) << 31))
        throw InputError(path, where, "more than 2^31 vertices");
}

/// What a whole mesh must be: triangles, normals and uvs on all primitives or none, finite.
void checkMesh(TriangleMesh& mesh, const AttributeCounts& counts, const std::string& path) {
    if (mesh.triangles.empty())
        throw InputError(path, "", "no triangles: expected a mesh primitive of mode TRIANGLES");
    if (counts.withNormals != 0 && counts.withNormals != counts.primitives)
        throw InputError(path, "",
                         "some primitives have NORMAL and some not: expected all or none");
    if (counts.withUvs != 0 && counts.withUvs != counts.primitives)
        throw InputError(path, "",
                         "some primitives have TEXCOORD_0 and some not: expected all or none");
    for (const Vec3& p : mesh.positions)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw InputError(path, "", "a node transform makes a position non-finite");
    for (Vec3& n : mesh.normals)
        if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) n = Vec3{0, 0, 1};
}

}  // namespace

TriangleMesh loadGltfMesh(const std::string& path, const std::string& nodeName) {
    const tinygltf::Model model = readModel(path);
    const std::vector<std::pair<int, Matrix>> instances = meshInstances(model, path, nodeName);
    TriangleMesh mesh;
    Reader reader(path, model);
    AttributeCounts counts;
    std::map<int, int> placed;  // instances of each mesh so far
    for (const auto& [meshIndex, world] : instances) {
        if (meshIndex >= int(model.meshes.size()))
            throw InputError(path, fmt::format("mesh {}", meshIndex), "the mesh does not exist");
        const tinygltf::Mesh& m = model.meshes[meshIndex];
        const int instance = placed[meshIndex]++;
        for (size_t p = 0; p < m.primitives.size(); ++p) {
            const tinygltf::Primitive& prim = m.primitives[p];
            if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) continue;
            const std::string where =
                fmt::format("mesh {} (\"{}\"), primitive {}", meshIndex, m.name, p);
            appendPrimitive(model, prim, world, reader, path, where, mesh, counts);
            // Labels: the mesh's name (its instance and primitive when there are several),
            // the primitive's material name.
            std::string group = m.name.empty() ? fmt::format("mesh{}", meshIndex) : m.name;
            if (instance > 0) group += fmt::format(".{}", instance);
            if (m.primitives.size() > 1) group += fmt::format(".p{}", p);
            std::string material;
            if (prim.material >= 0 && prim.material < int(model.materials.size()))
                material = model.materials[prim.material].name;
            auto label = [](std::vector<std::string>& names, const std::string& name) {
                auto it = std::find(names.begin(), names.end(), name);
                if (it == names.end()) it = names.insert(names.end(), name);
                return static_cast<uint32_t>(it - names.begin());
            };
            mesh.triangleGroups.resize(mesh.triangles.size(), label(mesh.groupNames, group));
            mesh.triangleMaterials.resize(mesh.triangles.size(),
                                          label(mesh.materialNames, material));
        }
    }
    checkMesh(mesh, counts, path);
    return mesh;
}

}  // namespace nenrin
