#include "renderer/texture_set/texture_set_files.h"

#include <fmt/format.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "renderer/exr_file.h"
#include "renderer/texture_set/folder_outputs.h"
#include "renderer/texture_set/pbr_finish.h"
#include "util/input_error.h"

namespace nenrin {

namespace {

struct MapFile {
    const char* file;
    const std::vector<float>* pixels;
    std::vector<std::string> channels;
    ExrValues values;
    const char* encoding;  ///< how texture-set.json describes the values
};

std::vector<MapFile> mapFiles(const UvMaps& maps) {
    return {
        {"basecolor.exr",
         &maps.baseColour,
         {"R", "G", "B"},
         ExrValues::SceneLinear,
         "colour: scene-linear Rec.709"},
        {"coverage.exr",
         &maps.coverage,
         {"Y"},
         ExrValues::Data,
         "data: 1 = texel on the mesh, 0 = gutter"},
        {"roughness.exr",
         &maps.roughness,
         {"Y"},
         ExrValues::Data,
         "data: perceptual roughness (alpha = r^2)"},
        {"normal.exr",
         &maps.normal,
         {"R", "G", "B"},
         ExrValues::Data,
         "data: tangent-space normal, 0.5 n + 0.5"},
        {"fibre.exr",
         &maps.fibre,
         {"R", "G", "B"},
         ExrValues::Data,
         "data: tangent-space fibre, 0.5 f + 0.5"},
        {"growth.exr",
         &maps.growth,
         {"T", "knot"},
         ExrValues::Data,
         "data: growth time (years), knot share"},
    };
}

void writeObj(const TriangleMesh& mesh, const std::string& objectName, const std::string& stem,
              const std::string& finalPath, const std::string& path) {
    std::ofstream obj(path);
    obj << "# nenrin bake uv: " << objectName << "\nmtllib " << stem << ".mtl\nusemtl " << stem
        << "\n";
    for (const Vec3& p : mesh.positions) obj << fmt::format("v {} {} {}\n", p.x, p.y, p.z);
    for (const auto& uv : mesh.uvs) obj << fmt::format("vt {} {}\n", uv[0], uv[1]);
    for (const Vec3& nrm : mesh.normals) obj << fmt::format("vn {} {} {}\n", nrm.x, nrm.y, nrm.z);
    for (const auto& t : mesh.triangles) {
        obj << "f";
        for (uint32_t v : t) {
            if (mesh.normals.empty())
                obj << fmt::format(" {}/{}", v + 1, v + 1);
            else
                obj << fmt::format(" {}/{}/{}", v + 1, v + 1, v + 1);
        }
        obj << "\n";
    }
    obj.flush();
    if (!obj) throw InputError(finalPath, "output", "could not write the mesh (disk full?)");
}

/// The MTL with the PBR extension keys Blender's OBJ importer, three.js and assimp read: Pr/Pm
/// for the base, Pc/Pcr for the coat, norm for the normal map. No map_Bump: the format reads it
/// as a height map. No aniso: MTL cannot carry a direction map, and an importer's default
/// tangent (Blender: radial about Z) would streak the wood like brushed metal.
std::string mtlText(const std::string& stem, const PbrFinish& p) {
    return fmt::format(
        "# nenrin bake uv (docs/uv-bake.md): linear EXR maps; roughness.exr and normal.exr are\n"
        "# data, not colour. The fibre direction (fibre.exr) has no MTL key: the Blender add-on\n"
        "# (blender/) and the glTF set wire it as the anisotropy tangent.\n"
        "newmtl {}\n"
        "Kd 1 1 1\n"
        "Ks 0.5 0.5 0.5\n"
        "Ni {}\n"
        "illum 2\n"
        "Pm 0\n"
        "Pr {:.4f}\n"
        "Pc {:.4f}\n"
        "Pcr {:.4f}\n"
        "map_Kd basecolor.exr\n"
        "map_Pr roughness.exr\n"
        "norm normal.exr\n",
        stem, p.ior, p.baseRoughness, p.coatWeight, p.coatRoughness);
}

std::string descriptionText(const UvMaps& maps, const std::string& objectName,
                            const std::string& stem,
                            const std::map<std::string, std::string>& metadata) {
    const PbrFinish p = pbrFinish(maps.finish);
    nlohmann::ordered_json j;
    j["format"] = "nenrin texture set";
    j["format_version"] = 1;
    j["object"] = objectName;
    j["mesh"] = stem + ".obj";
    j["material"] = stem + ".mtl";
    j["resolution"] = {maps.width, maps.height};
    j["tangent_frame"] =
        "tangent +u, bitangent +v (flipped on mirrored charts), normal: the mesh's; OpenGL "
        "Y+ normal maps (Blender, glTF)";
    nlohmann::ordered_json files;
    for (const MapFile& m : mapFiles(maps)) files[m.file] = m.encoding;
    j["maps"] = files;
    j["finish"] = {{"name", maps.finish.name},          {"coat_weight", p.coatWeight},
                   {"coat_roughness", p.coatRoughness}, {"ior", p.ior},
                   {"base_roughness", p.baseRoughness}, {"anisotropy", p.anisotropy},
                   {"fibre_strength", p.fibreStrength}};
    j["metadata"] = metadata;
    return j.dump(2) + "\n";
}

}  // namespace

std::string textureSetStem(const std::string& objectName) {
    std::string stem = objectName;
    for (char& c : stem)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
    return stem;
}

std::vector<std::string> writeTextureSet(const UvMaps& maps, const SceneObject& object,
                                         const std::string& folder,
                                         const std::map<std::string, std::string>& metadata) {
    FolderOutputs out(folder, "the maps");
    const std::string stem = textureSetStem(object.name);
    for (const MapFile& m : mapFiles(maps)) {
        const std::string& path = out.add(m.file);
        writeFloatExr(out.last(), path, maps.width, maps.height, m.channels, m.pixels->data(),
                      metadata, RowBand{}, m.values);
    }
    // The mesh and a material pointing at the maps, so the bake opens textured.
    {
        const std::string& path = out.add(stem + ".obj");
        writeObj(*object.mesh, object.name, stem, out.last(), path);
    }
    auto text = [&](const std::string& name, const std::string& content) {
        const std::string& path = out.add(name);
        std::ofstream f(path);
        f << content;
        f.flush();
        if (!f) throw InputError(out.last(), "output", "could not write it (disk full?)");
    };
    text(stem + ".mtl", mtlText(stem, pbrFinish(maps.finish)));
    text("texture-set.json", descriptionText(maps, object.name, stem, metadata));
    // Only now, with every file complete, do they get their names.
    return out.commit();
}

}  // namespace nenrin
