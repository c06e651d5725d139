#include "renderer/jobs/furniture_job.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>

#include "renderer/colour_management.h"
#include "renderer/furniture/crease_normals.h"
#include "renderer/furniture/furniture_plan.h"
#include "renderer/furniture/glued_panels.h"
#include "renderer/furniture/model_parts.h"
#include "renderer/furniture/part_charts.h"
#include "renderer/path_tracer.h"
#include "renderer/scene_file.h"
#include "renderer/texture_set/folder_outputs.h"
#include "renderer/texture_set/gltf_model.h"
#include "renderer/texture_set/gltf_texture_set.h"
#include "renderer/texture_set/uv_bake.h"
#include "renderer/texture_set/uv_raster.h"
#include "shader/finish.h"
#include "util/atomic_output.h"
#include "util/input_error.h"

namespace nenrin {

namespace fs = std::filesystem;

namespace {

/// The log when the user gives none: a straight trunk 10 m tall (concentric rings).
constexpr const char* kStraightTrunk =
    "{\n  \"description\": \"nenrin furniture's default log: a straight trunk, 10 m tall\",\n"
    "  \"elongation_speed\": 0.5,\n  \"trunk\": { \"points\": [[0, 0, 0], [0, 0, 10]] }\n}\n";

/// Gutter between a part's own charts, in uv units: 4 texels of a 1024 map.
constexpr double kChartGutter = 4.0 / 1024;

/// A part's own uvs can be baked on when every triangle has them, inside the unit square, with
/// area, and no two triangles share a texel of a 256 x 256 raster.
bool ownUvsUsable(const TriangleMesh& m) {
    if (m.uvs.empty()) return false;
    const UvRaster r = rasterizeUv(m, 256, 256);
    return r.overlappingTexels == 0 && r.trianglesOutsideUnitSquare == 0 &&
           r.degenerateTriangles == 0;
}

/// The diagonal (m) of furniture, from a footstool to a wardrobe: outside it, a warning.
constexpr double kPlausibleSize[2] = {0.25, 8};

/// A folder name-safe version of a part's name.
std::string fileName(size_t index, const std::string& name) {
    std::string safe;
    for (char c : name)
        safe += std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' ? c : '_';
    return fmt::format("{:03d}-{}.obj", index, safe.substr(0, 64));
}

std::string objText(const TriangleMesh& m) {
    std::string s = "# a part written by nenrin furniture (metres)\n";
    for (const Vec3& p : m.positions) s += fmt::format("v {:.9g} {:.9g} {:.9g}\n", p.x, p.y, p.z);
    for (const auto& uv : m.uvs) s += fmt::format("vt {:.9g} {:.9g}\n", uv[0], uv[1]);
    for (const Vec3& n : m.normals) s += fmt::format("vn {:.9g} {:.9g} {:.9g}\n", n.x, n.y, n.z);
    const bool uv = !m.uvs.empty(), normal = !m.normals.empty();
    auto corner = [&](uint32_t v) {
        const uint32_t i = v + 1;
        if (uv && normal) return fmt::format("{}/{}/{}", i, i, i);
        if (uv) return fmt::format("{}/{}", i, i);
        if (normal) return fmt::format("{}//{}", i, i);
        return fmt::format("{}", i);
    };
    for (const auto& t : m.triangles)
        s += fmt::format("f {} {} {}\n", corner(t[0]), corner(t[1]), corner(t[2]));
    return s;
}

nlohmann::json vec(const Vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }

/// scene.json: every part a mesh in its own place in the log, a camera framing the model from
/// the front right, above (+y up), a sun and sky, a floor under it.
nlohmann::json sceneJson(const std::vector<PartPlan>& plan, const std::vector<std::string>& files,
                         const std::string& skeleton, const TriangleMesh& model,
                         const FurnitureJob& job) {
    Vec3 lo, hi;
    meshBounds(model, lo, hi);
    const Vec3 centre = (lo + hi) * 0.5;
    const double radius = std::max(0.5 * length(hi - lo), 1e-3);
    const double fov = 35;
    const double distance = 1.15 * radius / std::tan(0.5 * fov * std::numbers::pi / 180);
    const Vec3 eye = centre + normalize(Vec3{1.0, 0.55, 1.5}) * distance;
    nlohmann::json materials = nlohmann::json::array(), objects = nlohmann::json::array();
    std::map<std::string, std::string> woodByGrain;
    for (const PartPlan& p : plan)
        if (p.wood && !woodByGrain.count(p.grain)) {
            const std::string name = fmt::format("wood-{}", woodByGrain.size());
            woodByGrain[p.grain] = name;
            nlohmann::json m = {
                {"name", name}, {"type", "wood"}, {"skeleton", skeleton}, {"finish", job.finish}};
            if (!p.grain.empty()) m["grain"] = fs::absolute(p.grain).string();
            materials.push_back(m);
        }
    materials.push_back({{"name", "not-wood"}, {"type", "diffuse"}, {"colour", 0.45}});
    materials.push_back({{"name", "floor"}, {"type", "diffuse"}, {"colour", 0.6}});
    for (size_t i = 0; i < plan.size(); ++i) {
        const PartPlan& p = plan[i];
        nlohmann::json o = {{"type", "mesh"}, {"name", p.name}, {"file", "parts/" + files[i]}};
        if (p.wood && p.board) {
            o["material"] = woodByGrain[p.grain];
            const Rgb& t = p.board->tint;
            o["log"] = {{"position", vec(p.treeFromModel.origin)},
                        {"rotate", vec(logRotateDegrees(p.treeFromModel))},
                        {"tint", {t.r, t.g, t.b}}};
        } else {
            o["material"] = "not-wood";
        }
        objects.push_back(o);
    }
    const Vec3 floor{6 * radius, 0.01 * radius, 6 * radius};
    objects.push_back({{"type", "box"},
                       {"name", "floor"},
                       {"size", vec(floor)},
                       {"position", vec({centre.x, lo.y - 0.5 * floor.y, centre.z})},
                       {"material", "floor"}});
    return {{"description", fmt::format("{} in solid wood: every part its own board (nenrin "
                                        "furniture; parts.json)",
                                        fs::path(job.model).filename().string())},
            {"camera", {{"position", vec(eye)}, {"look_at", vec(centre)}, {"fov", fov}}},
            {"render",
             {{"resolution", {job.previewWidth, job.previewHeight}},
              {"spp", job.previewSpp},
              {"max_depth", 3},
              {"seed", 1}}},
            {"lights", nlohmann::json::array(
                           {{{"type", "sun"}, {"direction", {0.4, 0.8, 0.5}}, {"irradiance", 3}},
                            {{"type", "environment"}, {"colour", {0.45, 0.47, 0.5}}}})},
            {"materials", materials},
            {"objects", objects}};
}

/// A private folder (under the system's temporary folder) for the files the preview render
/// reads, removed however the job ends.
class WorkFolder {
public:
    WorkFolder()
        : path_(fs::temp_directory_path() / fmt::format("nenrin-furniture-{}", ::getpid())) {
        fs::remove_all(path_);
        fs::create_directories(path_ / "parts");
    }
    ~WorkFolder() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
};

void writePlain(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    if (!out.flush()) throw InputError(path.string(), "", "cannot write (disk full?)");
}

}  // namespace

Vec3 logRotateDegrees(const RigidTransform& treeFromObject) {
    const RigidTransform standing =
        RigidTransform::fromAxes({1, 0, 0}, {0, 0, 1}, {0, -1, 0}, {0, 0, 0});
    RigidTransform r = treeFromObject;
    r.origin = {};
    const RigidTransform m = standing.inverse() * r;  // = Rz(c) Ry(b) Rx(a)
    const double deg = 180 / std::numbers::pi;
    const double sb = std::clamp(-m.x.z, -1.0, 1.0);
    if (std::abs(sb) > 1 - 1e-12)  // gimbal lock: only a - c (or a + c) is defined
        return {0, std::asin(sb) * deg, std::atan2(-m.y.x, m.y.y) * deg};
    return {std::atan2(m.y.z, m.z.z) * deg, std::asin(sb) * deg, std::atan2(m.x.y, m.x.x) * deg};
}

namespace {

/// The model loaded in metres, its parts, and a warning when its size is implausible.
struct LoadedModel {
    TriangleMesh mesh;
    std::vector<ModelPart> parts;
    std::string sizeWarning;
};

LoadedModel loadModel(const FurnitureJob& job) {
    LoadedModel m;
    m.mesh = loadFurnitureModel(job.model, metresPerUnit(job.unit));
    Vec3 lo, hi;
    meshBounds(m.mesh, lo, hi);
    const double diagonal = length(hi - lo);
    if (diagonal < kPlausibleSize[0] || diagonal > kPlausibleSize[1])
        m.sizeWarning = fmt::format(
            "the model is {:.3g} m across in --unit {}: implausible for furniture (is the unit "
            "right? the chair of sweethome3d-furniture is in cm)",
            diagonal, job.unit);
    m.parts = splitModelParts(m.mesh, job.model);
    // Normals where the model has none, so the render, the bakes and the glTF shade alike.
    for (ModelPart& part : m.parts)
        if (part.mesh.normals.empty()) part.mesh = withCreaseNormals(part.mesh);
    return m;
}

/// The cut plan of every part (the log's skeleton already written where `skeleton` says).
std::vector<PartPlan> planParts(const FurnitureJob& job, const std::vector<ModelPart>& parts,
                                const std::string& sizeWarning, const std::string& skeleton,
                                const PlanChoices& choices) {
    FurniturePlanRequest request;
    // Absolute, so that parts.json and scene.json work from any folder.
    request.grain = fs::absolute(job.grain).string();
    request.skeleton = skeleton;
    request.cut.seed = static_cast<uint64_t>(job.seed);
    request.cut.sawing = job.sawing == "flat"      ? Sawing::Flat
                         : job.sawing == "quarter" ? Sawing::Quarter
                                                   : Sawing::Mixed;
    request.choices = choices.parts;
    request.grainByMaterial = choices.grainByMaterial;
    TreeCache trees;
    try {
        return planFurniture(parts, request, trees);
    } catch (const InputError& e) {
        // A board too big for the log is most often a model in other units: say so.
        if (sizeWarning.empty()) throw;
        throw InputError(e.file(), e.where(), e.message() + "; " + sizeWarning);
    }
}

/// Bakes part `index` of the work folder's scene onto its uvs and writes its texture set
/// (glTF with PNG maps, docs/uv-bake.md) into `folder`.
GltfTextureSet writePartTextures(const Scene& scene, size_t index, const std::string& folder,
                                 const std::string& finalScene, const FurnitureJob& job) {
    const SceneObject& object = scene.objects[index];
    UvBakeOptions options;
    options.width = options.height = job.textureSize;
    options.threads = job.threads;
    options.quiet = true;
    const UvMaps maps = bakeUvMaps(scene, object, options);
    fs::create_directories(folder);
    const std::map<std::string, std::string> metadata{
        {"version", NENRIN_VERSION}, {"scene", finalScene}, {"object", object.name}};
    return writeGltfTextureSet(maps, object, folder, metadata);
}

/// A plan's entries for parts the model does not have would silently do nothing: say so.
void warnUnusedChoices(const std::map<std::string, PartChoice>& choices,
                       const std::vector<ModelPart>& parts, const std::string& planFile,
                       std::vector<std::string>& warnings) {
    for (const auto& entry : choices) {
        const std::string& name = entry.first;  // a structured binding: clang 14 cannot capture it
        if (std::none_of(parts.begin(), parts.end(),
                         [&](const ModelPart& p) { return p.name == name || p.panel == name; }))
            warnings.push_back(fmt::format(
                "{}: part \"{}\" is not in the model: its choices were not used", planFile, name));
    }
}

/// Every wood part's texture set in its own folder (textures/NNN-NAME, noted in `planned`),
/// and the whole model as one glTF, DIR/MODEL.glb, whose wood parts show those sets.
void writeTextureSets(const FurnitureJob& job, const Scene& scene,
                      const std::vector<ModelPart>& parts, const std::vector<PartPlan>& plan,
                      const std::vector<TriangleMesh>& meshes,
                      const std::vector<std::string>& files, nlohmann::json& planned,
                      FurnitureReport& report) {
    const fs::path out = job.output;
    const std::string scenePath = (out / "scene.json").string();
    std::vector<GltfNode> nodes(parts.size());
    std::vector<GltfImage> images;
    for (size_t i = 0; i < parts.size(); ++i) {
        GltfNode& node = nodes[i];
        node.name = parts[i].name;
        node.mesh = &meshes[i];
        node.materialName = parts[i].material.empty() ? "not-wood" : parts[i].material;
        if (!plan[i].wood) continue;
        const std::string set = "textures/" + fs::path(files[i]).stem().string();
        planned[i]["textures"] = set;
        GltfTextureSet written = writePartTextures(scene, i, (out / set).string(), scenePath, job);
        report.written.insert(report.written.end(), written.written.begin(), written.written.end());
        node.materialName = fs::path(files[i]).stem().string();
        node.finish = written.finish;
        for (size_t k = 0; k < written.images.size(); ++k) {
            node.images[k] = int(images.size());
            images.push_back({set + "/" + written.images[k].uri, std::move(written.images[k].png)});
        }
    }
    FolderOutputs model(out.string(), "the model's glTF files");
    writeGltfModel(nodes, images, fs::path(job.model).stem().string(),
                   std::string("nenrin ") + NENRIN_VERSION, model);
    for (const std::string& f : model.commit()) report.written.push_back(f);
}

}  // namespace

double metresPerUnit(const std::string& unit) {
    if (unit == "m") return 1;
    if (unit == "cm") return 0.01;
    if (unit == "mm") return 0.001;
    throw InputError("command line", "--unit",
                     fmt::format("expected mm, cm or m, found \"{}\"", unit));
}

namespace {

/// The command line's settings and the output folder, checked before any work: a bad unit,
/// finish or folder fails at once.
void checkJob(const FurnitureJob& job) {
    metresPerUnit(job.unit);
    Finish finish;
    if (!finishPreset(job.finish, finish))
        throw InputError(
            "command line", "--finish",
            fmt::format("expected one of {}, found \"{}\"", finishPresetNames(), job.finish));
    const fs::path out = job.output;
    if (fs::exists(out) && !fs::is_directory(out))
        throw InputError("command line", "-o", fmt::format("{}: not a folder", job.output));
    // The folder, or the one it will be made in, must be writable before the work starts.
    const fs::path parent = out.has_parent_path() ? out.parent_path() : fs::path(".");
    checkOutputPath(((fs::is_directory(out) ? out : parent) / "parts.json").string());
}

}  // namespace

FurnitureReport runFurnitureJob(const FurnitureJob& job) {
    checkJob(job);
    const fs::path out = job.output;
    FurnitureReport report;
    const LoadedModel model = loadModel(job);
    if (!model.sizeWarning.empty()) report.warnings.push_back(model.sizeWarning);

    WorkFolder work;
    std::string skeleton = job.skeleton;
    if (skeleton.empty()) {
        writePlain(work.path() / "skeleton.json", kStraightTrunk);
        skeleton = (work.path() / "skeleton.json").string();
    }
    PlanChoices userChoices = job.plan.empty() ? PlanChoices{} : readPlanChoices(job.plan);
    for (const auto& [material, grain] : job.grainByMaterial)
        userChoices.grainByMaterial[material] = fs::absolute(grain).string();
    const std::map<std::string, PartChoice>& choices = userChoices.parts;
    // Wide panels become boards glued side by side, each a part.
    const std::vector<ModelPart> parts = glueWidePanels(model.parts, choices);
    const std::vector<PartPlan> plan =
        planParts(job, parts, model.sizeWarning, skeleton, userChoices);
    warnUnusedChoices(choices, parts, job.plan, report.warnings);

    // The parts with uvs a texture set can be baked on: the model's own where they are
    // usable, else charts of their own.
    std::vector<TriangleMesh> meshes;
    std::vector<bool> charted;
    for (size_t i = 0; i < parts.size(); ++i) {
        charted.push_back(!ownUvsUsable(parts[i].mesh));
        meshes.push_back(charted.back() ? chartPart(parts[i].mesh, plan[i].frame, kChartGutter).mesh
                                        : parts[i].mesh);
    }
    // The parts and the scene, first in the work folder for the preview render.
    std::vector<std::string> files;
    for (size_t i = 0; i < parts.size(); ++i) files.push_back(fileName(i, parts[i].name));
    const std::string finalSkeleton = job.skeleton.empty()
                                          ? (fs::absolute(out) / "skeleton.json").string()
                                          : fs::absolute(job.skeleton).string();
    nlohmann::json scene = sceneJson(plan, files, fs::absolute(skeleton).string(), model.mesh, job);
    std::vector<std::string> objTexts;
    for (size_t i = 0; i < parts.size(); ++i) {
        objTexts.push_back(objText(meshes[i]));
        writePlain(work.path() / "parts" / files[i], objTexts[i]);
    }
    writePlain(work.path() / "scene.json", scene.dump(2));
    std::unique_ptr<Scene> loaded = loadScene((work.path() / "scene.json").string());
    RenderOptions options;
    options.threads = job.threads;
    options.quiet = job.quiet;
    RenderStats stats;
    Film film = renderScene(*loaded, options, stats);

    // The outputs, all through the command's transaction.
    fs::create_directories(out / "parts");
    for (size_t i = 0; i < parts.size(); ++i) {
        const std::string path = (out / "parts" / files[i]).string();
        writeTextAtomically(path, objTexts[i], "part mesh");
        report.written.push_back(path);
    }
    if (job.skeleton.empty()) {
        writeTextAtomically(finalSkeleton, kStraightTrunk, "skeleton");
        report.written.push_back(finalSkeleton);
    }
    for (auto& m : scene["materials"])
        if (m.contains("skeleton")) m["skeleton"] = finalSkeleton;
    const std::string scenePath = (out / "scene.json").string();
    nlohmann::json planned = planJson(plan);
    for (size_t i = 0; i < parts.size(); ++i) {
        planned[i]["file"] = "parts/" + files[i];
        planned[i]["uvs"] = charted[i] ? "charts" : "model";
    }
    if (job.textureSize > 0)
        writeTextureSets(job, *loaded, parts, plan, meshes, files, planned, report);
    const nlohmann::json partsJson = {{"model", fs::absolute(job.model).string()},
                                      {"unit", job.unit},
                                      {"skeleton", finalSkeleton},
                                      {"grain", fs::absolute(job.grain).string()},
                                      {"grain_by_material", userChoices.grainByMaterial},
                                      {"seed", job.seed},
                                      {"parts", planned}};
    const std::string partsPath = (out / "parts.json").string();
    const std::string previewPath = (out / "preview.png").string();
    writeTextAtomically(partsPath, partsJson.dump(2) + "\n", "parts plan");
    writeTextAtomically(scenePath, scene.dump(2) + "\n", "scene");
    writePreviewPng(previewPath, film.rgb, film.width, film.height);
    report.written.insert(report.written.end(), {partsPath, scenePath, previewPath});
    report.parts = plan.size();
    for (const PartPlan& p : plan) {
        report.woodParts += p.wood;
        for (const std::string& n : p.notes) report.warnings.push_back(p.name + ": " + n);
    }
    return report;
}

}  // namespace nenrin
