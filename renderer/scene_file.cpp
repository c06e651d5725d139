#include "renderer/scene_file.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <map>

#include "grain/grain_params.h"
#include "renderer/geometry/gltf_mesh.h"
#include "renderer/products/cut_plan.h"
#include "renderer/products/log_slice.h"
#include "skeleton/skeleton_file.h"
#include "util/json_reader.h"
#include "util/limits.h"

namespace nenrin {

namespace {

// Caps that catch typos (an extra zero) before they cost hours or all memory.
constexpr int kMaxLamellae = 100000;

/// A path in the scene file, relative to it; recorded as one of the scene's inputs.
std::string resolve(Scene& scene, const std::string& relative) {
    std::string path = pathRelativeTo(scene.file, relative);
    scene.inputFiles.push_back(path);
    return path;
}

/// A colour: [r, g, b] or one number for grey, each >= 0.
/// Loads a file the scene names at `key`: an error in that file also names the scene and the
/// key that refers to it ("room.json: lights[0].map: sky.exr: cannot read the image ...").
template <typename Load>
auto loadReferenced(JsonReader& r, const std::string& key, Load load) {
    try {
        return load();
    } catch (const InputError& e) {
        throw r.error(key, e.what());
    }
}

Rgb colourOf(JsonReader& r, const std::string& key, const Rgb& fallback) {
    if (!r.has(key)) return fallback;
    if (r.isNumber(key)) {
        double v = r.nonNegative(key, 0);
        return {v, v, v};
    }
    Vec3 v = r.vec3(key, {});
    if (v.x < 0 || v.y < 0 || v.z < 0) throw r.error(key, "expected colour components >= 0");
    return {v.x, v.y, v.z};
}

Vec3 unitVector(JsonReader& r, const std::string& key, const Vec3& fallback) {
    Vec3 v = r.vec3(key, fallback);
    if (lengthSquared(v) < 1e-20) throw r.error(key, "expected a non-zero vector");
    return normalize(v);
}

/// "position" and "rotate" ([x, y, z] degrees, applied about x, then y, then z).
RigidTransform placement(JsonReader& r, const std::string& positionKey = "position") {
    Vec3 angles = r.vec3("rotate", {});
    RigidTransform t = RigidTransform::rotation({0, 0, 1}, radians(angles.z)) *
                       RigidTransform::rotation({0, 1, 0}, radians(angles.y)) *
                       RigidTransform::rotation({1, 0, 0}, radians(angles.x));
    t.origin = r.vec3(positionKey, {});
    return t;
}

CameraSpec readCamera(JsonReader& r) {
    CameraSpec c;
    c.position = r.requireVec3("position");
    c.lookAt = r.requireVec3("look_at");
    c.up = unitVector(r, "up", {0, 1, 0});
    c.verticalFov = radians(r.inRange("fov", 40, 0.01, 179));
    c.apertureRadius = r.nonNegative("aperture_radius", 0);
    c.focusDistance = r.nonNegative("focus_distance", 0);
    Vec3 forward = c.lookAt - c.position;
    if (lengthSquared(forward) < 1e-20) throw r.error("look_at", "must differ from position");
    if (lengthSquared(cross(normalize(forward), c.up)) < 1e-12)
        throw r.error("up", "must not be parallel to the view direction");
    r.finish();
    return c;
}

RenderSettings readSettings(JsonReader& r) {
    RenderSettings s;
    if (r.has("resolution")) {
        std::vector<double> res = r.numberList("resolution");
        if (res.size() != 2 || res[0] != std::floor(res[0]) || res[1] != std::floor(res[1]) ||
            !(std::abs(res[0]) <= kMaxImageSide && std::abs(res[1]) <= kMaxImageSide) ||
            !imageSizeAllowed(static_cast<long long>(res[0]), static_cast<long long>(res[1])))
            throw r.error("resolution",
                          fmt::format("expected [width, height], whole numbers in 1..{} and at "
                                      "most {} pixels",
                                      kMaxImageSide, kMaxImagePixels));
        s.width = static_cast<int>(res[0]);
        s.height = static_cast<int>(res[1]);
    }
    s.spp = static_cast<int>(r.integer("spp", s.spp, 1, kMaxSpp));
    s.maxDepth = static_cast<int>(r.integer("max_depth", s.maxDepth, 1, 64));
    s.noiseThreshold = r.inRange("noise_threshold", 0, 0, 1);
    s.minSpp = static_cast<int>(r.integer("min_spp", 0, 0, kMaxSpp));
    s.seed = static_cast<uint64_t>(r.integer("seed", 1, 0, (1LL << 53)));
    const std::string selection =
        r.choice("light_selection", "auto", {"auto", "all", "importance"});
    s.lightSelection = selection == "all"          ? LightSelectionMode::All
                       : selection == "importance" ? LightSelectionMode::Importance
                                                   : LightSelectionMode::Auto;
    r.finish();
    return s;
}

Light readLight(JsonReader& r, Scene& scene) {
    Light l;
    std::string type = r.choice("type", "", {"distant", "sun", "point", "rect", "environment"});
    Rgb colour = colourOf(r, "colour", {1, 1, 1});
    if (type == "distant" || type == "sun") {
        l.type = LightType::Distant;
        l.direction = unitVector(r, "direction", {0, 1, 0});
        if (!r.has("direction"))
            throw r.error("direction", "missing: the direction towards the light");
        double e = r.nonNegative("irradiance", 3);
        l.power = colour * e;
    } else if (type == "point") {
        l.type = LightType::Point;
        l.position = r.requireVec3("position");
        l.power = colour * r.nonNegative("intensity", 1);
    } else if (type == "rect") {
        l.type = LightType::Rect;
        l.corner = r.requireVec3("corner");
        l.edgeU = r.requireVec3("edge_u");
        l.edgeV = r.requireVec3("edge_v");
        Vec3 n = cross(l.edgeU, l.edgeV);
        l.area = length(n);
        if (!(l.area > 1e-12)) throw r.error("edge_v", "the rectangle has no area");
        l.normal = n / l.area;
        l.power = colour * r.nonNegative("radiance", 1);
    } else {
        l.type = LightType::Environment;
        double intensity = r.nonNegative("intensity", 1);
        if (r.has("map")) {
            std::string map = resolve(scene, r.string("map", ""));
            const double rotation = radians(r.number("rotation", 0));
            l.environment = loadReferenced(r, "map", [&] {
                return std::make_shared<EnvironmentMap>(
                    EnvironmentMap::load(map, intensity, rotation));
            });
            if (r.has("colour")) throw r.error("colour", "use either \"map\" or \"colour\"");
        } else {
            l.environment =
                std::make_shared<EnvironmentMap>(EnvironmentMap::constant(colour * intensity));
        }
    }
    r.finish();
    return l;
}

/// Loads (once per skeleton + grain pair) the tree a wood material cuts from.
const WoodTree& woodTree(Scene& scene, const std::string& skeletonFile,
                         const std::string& grainFile) {
    for (const auto& t : scene.trees)
        if (t->skeletonFile == skeletonFile && t->grainFile == grainFile) return *t;
    auto t = std::make_unique<WoodTree>();
    t->skeletonFile = skeletonFile;
    t->grainFile = grainFile;
    t->grown = GrownTree::load(skeletonFile, grainFile);
    scene.trees.push_back(std::move(t));
    return *scene.trees.back();
}

Material readMaterial(JsonReader& r, Scene& scene) {
    Material m;
    m.name = r.string("name", "");
    if (m.name.empty()) throw r.error("name", "missing: every material needs a name");
    std::string type = r.choice("type", "", {"diffuse", "glossy", "metal", "wood", "textured"});
    if (type == "textured") {
        m.type = MaterialType::Textured;
        if (!r.has("base_colour")) throw r.error("base_colour", "missing: the base colour map");
        auto texture = [&](const std::string& key, TextureValues values) {
            const std::string file = resolve(scene, r.string(key, ""));
            return loadReferenced(r, key, [&] {
                return std::make_shared<ImageTexture>(ImageTexture::load(file, 3, values));
            });
        };
        m.baseColourMap = texture("base_colour", TextureValues::Colour);
        if (r.has("normal")) m.normalMap = texture("normal", TextureValues::Data);
        if (r.has("fibre") && r.has("anisotropy"))
            throw r.error("anisotropy", "give the fibre map or the anisotropy map, not both");
        if (r.has("fibre")) m.fibreMap = texture("fibre", TextureValues::Data);
        if (r.has("anisotropy")) m.anisotropyMap = texture("anisotropy", TextureValues::Data);
        m.finish = readFinish(r);
    } else if (type == "wood") {
        m.type = MaterialType::Wood;
        if (!r.has("skeleton")) throw r.error("skeleton", "missing: the skeleton JSON file");
        std::string skeleton = resolve(scene, r.string("skeleton", ""));
        std::string grain = r.has("grain") ? resolve(scene, r.string("grain", "")) : "";
        const Finish finish = readFinish(r);
        // An error in the skeleton or grain file also names the scene's key that refers to it.
        const WoodTree* loaded = nullptr;
        try {
            loaded = &woodTree(scene, skeleton, grain);
        } catch (const InputError& e) {
            throw r.error(!grain.empty() && e.file() == grain ? "grain" : "skeleton", e.what());
        }
        const WoodTree& tree = *loaded;
        scene.woodShaders.push_back(std::make_unique<WoodShader>(tree.grown->field(), finish));
        m.wood = scene.woodShaders.back().get();
    } else {
        m.type = type == "diffuse"  ? MaterialType::Diffuse
                 : type == "glossy" ? MaterialType::Glossy
                                    : MaterialType::Metal;
        m.colour = colourOf(r, "colour", m.colour);
        if (m.colour.r > 1 || m.colour.g > 1 || m.colour.b > 1)
            throw r.error("colour", "expected reflectances in [0, 1]");
        if (m.type != MaterialType::Diffuse) m.roughness = r.inRange("roughness", 0.2, 0.001, 1);
    }
    r.finish();
    return m;
}

CutPlanParams readCutPlan(JsonReader& parent) {
    CutPlanParams c;
    auto r = parent.object("cut");
    if (!r) return c;
    c.seed = static_cast<uint64_t>(r->integer("seed", 1, 0, (1LL << 53)));
    std::string sawing = r->choice("sawing", "mixed", {"flat", "quarter", "mixed"});
    c.sawing = sawing == "flat"      ? Sawing::Flat
               : sawing == "quarter" ? Sawing::Quarter
                                     : Sawing::Mixed;
    c.bottom = r->nonNegative("bottom", c.bottom);
    c.top = r->nonNegative("top", 0);
    if (c.top > 0 && c.top <= c.bottom) throw r->error("top", "must lie above \"bottom\"");
    c.maxRadius = r->positive("max_radius", c.maxRadius);
    c.margin = r->nonNegative("margin", c.margin);
    c.colourVariation = r->inRange("colour_variation", c.colourVariation, 0, 5);
    r->finish();
    return c;
}

/// Every board of the layout gets its cut from the log and a scene-wide id.
void cutLamellae(LaminatedLayout& layout, const GrowthField& field, const CutPlanParams& plan,
                 int32_t& nextId, const JsonReader& where) {
    for (size_t i = 0; i < layout.lamellae.size(); ++i) {
        Lamella& l = layout.lamellae[i];
        Vec3 extent = l.upper - l.lower;
        int widthAxis = l.lengthAxis == 0 ? 2 : 0;
        double length = extent[l.lengthAxis], width = extent[widthAxis], thickness = extent.y;
        auto cut = cutBoard(field, plan, length, width, thickness, i);
        if (!cut) {
            double lo, hi;
            trunkHeightRange(field.skeleton(), lo, hi);
            throw where.error(
                "cut", fmt::format("board {} ({:.3g} x {:.3g} x {:.3g} m) does not fit in the "
                                   "log between heights {:.3g} and {:.3g} m of a {:.3g} m trunk: "
                                   "use smaller boards, another height window or a later "
                                   "felling time",
                                   i, length, width, thickness, plan.bottom,
                                   plan.top > 0 ? plan.top : lo + 0.7 * (hi - lo), hi - lo));
        }
        l.id = nextId++;
        l.treeFromLamella = cut->treeFromLamella;
        l.tint = cut->tint;
        l.treeFromProduct = l.treeFromLamella * l.lamellaFromProduct;
    }
}

/// Where solid (not laminated) wood sits in the tree: by default the object's +y (up in the
/// scene) runs along the trunk (+z in tree space), its origin on the pith at height 1 m.
RigidTransform readLogPlacement(JsonReader& parent, Rgb& boardTint) {
    RigidTransform treeFromObject =
        RigidTransform::fromAxes({1, 0, 0}, {0, 0, 1}, {0, -1, 0}, {0, 0, 1});
    auto r = parent.object("log");
    if (!r) return treeFromObject;
    const bool hasPosition = r->has("position");
    RigidTransform place = placement(*r);
    if (!hasPosition) place.origin = {0, 0, 1};
    if (r->has("tint")) {
        const Vec3 t = r->vec3("tint", {1, 1, 1});
        if (!(t.x >= 0 && t.y >= 0 && t.z >= 0 && t.x <= 2 && t.y <= 2 && t.z <= 2))
            throw r->error("tint", "expected three factors in [0, 2]");
        boardTint = {t.x, t.y, t.z};
    }
    r->finish();
    // "position" is in tree space, "rotate" turns the object before it is placed.
    RigidTransform rotateObject = place;
    rotateObject.origin = {};
    RigidTransform t = treeFromObject * rotateObject;
    t.origin = place.origin;
    return t;
}

/// A box's size, or a mesh's triangles (OBJ or glTF, scaled).
void readPlainShape(JsonReader& r, Scene& scene, SceneObject& o) {
    if (o.type == "box") {
        o.size = r.requireVec3("size");
        if (!(o.size.x > 0 && o.size.y > 0 && o.size.z > 0))
            throw r.error("size", "expected three sizes > 0");
        return;
    }
    o.shape = ShapeType::Mesh;
    if (!r.has("file")) throw r.error("file", "missing: the OBJ or glTF file");
    const std::string file = resolve(scene, r.string("file", ""));
    const std::string node = r.string("node", "");
    if (!node.empty() && !isGltfPath(file))
        throw r.error("node", "only a glTF file (.gltf, .glb) has nodes");
    auto mesh = loadReferenced(r, "file", [&] {
        return std::make_shared<TriangleMesh>(isGltfPath(file) ? loadGltfMesh(file, node)
                                                               : loadObjMesh(file));
    });
    double scale = r.positive("scale", 1);
    for (Vec3& p : mesh->positions) p = p * scale;
    o.mesh = mesh;
}

/// A disc cut across the trunk at a height, with its bark and radial checks.
void readLogSlice(JsonReader& r, const GrowthField& field, SceneObject& o) {
    LogSliceParams slice;
    slice.height = r.requireNumber("height");
    slice.thickness = r.positive("thickness", slice.thickness);
    slice.bark = r.nonNegative("bark", slice.bark);
    slice.maxRadius = r.positive("max_radius", slice.maxRadius);
    if (auto c = r.object("checks")) {
        slice.checks = static_cast<int>(c->integer("count", slice.checks, 0, 64));
        slice.checkDepth = c->inRange("depth", slice.checkDepth, 0, 0.9);
        slice.checkWidth = c->inRange("width", slice.checkWidth, 0, 0.05);
        slice.checkSeed = static_cast<uint64_t>(c->integer("seed", 1, 0, 1LL << 53));
        c->finish();
    }
    double lo, hi;
    trunkHeightRange(field.skeleton(), lo, hi);
    if (slice.height - 0.5 * slice.thickness < lo || slice.height + 0.5 * slice.thickness > hi)
        throw r.error("height", fmt::format("the slice must lie on the trunk, between {:.3g} "
                                            "and {:.3g} m",
                                            lo, hi));
    o.shape = ShapeType::Mesh;
    o.mesh = std::make_shared<TriangleMesh>(logSliceMesh(field, slice));
    o.treeFromObject = logSliceTreeFromObject(field, slice);
}

/// A glulam beam: lamellae stacked, each of finger-jointed pieces (or whole boards).
std::shared_ptr<LaminatedLayout> readGlulam(JsonReader& r, const GrowthField& field,
                                            int32_t& nextLamella) {
    int count = static_cast<int>(r.integer("lamellae", 6, 1, 200));
    double thickness = r.positive("lamella_thickness", 0.04);
    double width = r.positive("width", 0.14);
    double length = r.positive("length", 2.0);
    double minPiece = 0, maxPiece = 0;
    FingerJointProfile fingers;
    if (r.isBoolean("finger_joints")) {
        if (r.boolean("finger_joints", false))
            throw r.error("finger_joints", "expected false or an object {min_length, ...}");
    } else if (auto f = r.object("finger_joints")) {
        minPiece = f->positive("min_length", 0.9);
        maxPiece = f->positive("max_length", 2.4);
        if (maxPiece < minPiece) throw f->error("max_length", "must be >= min_length");
        // Checked before the layout is drawn: 1e-6 m pieces once grew to 24 GB.
        double boards = count * std::ceil(length / minPiece);
        if (boards > kMaxLamellae)
            throw f->error("min_length",
                           fmt::format("{} m pieces of {} lamellae {} m long could make {:.3g} "
                                       "boards: expected at most {}",
                                       minPiece, count, length, boards, kMaxLamellae));
        fingers.length = f->nonNegative("finger_length", fingers.length);
        fingers.pitch = f->positive("pitch", fingers.pitch);
        f->finish();
    }
    CutPlanParams plan = readCutPlan(r);
    auto layout = std::make_shared<LaminatedLayout>(
        glulamLayout(count, thickness, width, length, minPiece, maxPiece, plan.seed));
    layout->fingers = fingers;
    cutLamellae(*layout, field, plan, nextLamella, r);
    return layout;
}

/// Cross-laminated timber: an odd number of layers of boards, each crossing the one below.
std::shared_ptr<LaminatedLayout> readClt(JsonReader& r, const GrowthField& field,
                                         int32_t& nextLamella) {
    int layers = static_cast<int>(r.integer("layers", 5, 1, 99));
    if (layers % 2 == 0) throw r.error("layers", "expected an odd number of crossed layers");
    double thickness = r.positive("layer_thickness", 0.03);
    double boardWidth = r.positive("board_width", 0.15);
    double length = r.positive("length", 1.2), width = r.positive("width", 0.9);
    if (std::ceil(length / boardWidth) * std::ceil(width / boardWidth) * layers > kMaxLamellae)
        throw r.error("board_width", "too many boards (over 100000)");
    CutPlanParams plan = readCutPlan(r);
    auto layout =
        std::make_shared<LaminatedLayout>(cltLayout(layers, thickness, boardWidth, length, width));
    cutLamellae(*layout, field, plan, nextLamella, r);
    return layout;
}

/// A table top: boards glued edge to edge.
std::shared_ptr<LaminatedLayout> readTableTop(JsonReader& r, const GrowthField& field,
                                              int32_t& nextLamella) {
    int boards = static_cast<int>(r.integer("boards", 6, 1, 1000));
    double thickness = r.positive("thickness", 0.03);
    double width = r.positive("width", 0.8), length = r.positive("length", 1.6);
    CutPlanParams plan = readCutPlan(r);
    auto layout =
        std::make_shared<LaminatedLayout>(edgeGluedLayout(boards, thickness, width, length));
    cutLamellae(*layout, field, plan, nextLamella, r);
    return layout;
}

/// The glue lines of a laminated product: width and colour.
void readGlue(JsonReader& r, LaminatedLayout& layout) {
    if (auto g = r.object("glue")) {
        layout.glue.width = g->nonNegative("width", layout.glue.width);
        Rgb c = colourOf(*g, "colour",
                         {layout.glue.colour[0], layout.glue.colour[1], layout.glue.colour[2]});
        layout.glue.colour[0] = c.r;
        layout.glue.colour[1] = c.g;
        layout.glue.colour[2] = c.b;
        g->finish();
    }
}

SceneObject readObject(JsonReader& r, Scene& scene,
                       const std::map<std::string, uint32_t>& materials, int32_t& nextLamella) {
    SceneObject o;
    o.type = r.choice("type", "", {"box", "mesh", "log_slice", "glulam", "clt", "table_top"});
    o.name = r.string("name", fmt::format("{}{}", o.type, scene.objects.size()));
    std::string materialName = r.string("material", "");
    auto m = materials.find(materialName);
    if (m == materials.end())
        throw r.error("material", materialName.empty()
                                      ? "missing: the name of a material"
                                      : fmt::format("no material named \"{}\"", materialName));
    o.material = m->second;
    const Material& material = scene.materials[o.material];
    o.worldFromObject = placement(r);
    const bool wood = material.type == MaterialType::Wood;

    if (o.type == "box" || o.type == "mesh") {
        readPlainShape(r, scene, o);
        if (wood) o.treeFromObject = readLogPlacement(r, o.boardTint);
    } else if (o.type == "log_slice") {
        if (!wood) throw r.error("material", "a log slice needs a wood material");
        readLogSlice(r, material.wood->field(), o);
    } else {
        if (!wood)
            throw r.error("material",
                          fmt::format("a {} is made of boards: it needs a wood material", o.type));
        const GrowthField& field = material.wood->field();
        std::shared_ptr<LaminatedLayout> layout =
            o.type == "glulam" ? readGlulam(r, field, nextLamella)
            : o.type == "clt"  ? readClt(r, field, nextLamella)
                               : readTableTop(r, field, nextLamella);
        readGlue(r, *layout);
        o.size = layout->size;
        o.layout = layout;
    }
    r.finish();
    return o;
}

void applyOverrides(nlohmann::json& json, const SceneOverrides& overrides,
                    const std::string& path) {
    for (const auto& [pointerText, value] : overrides.values) {
        nlohmann::json::json_pointer pointer;
        try {
            pointer = nlohmann::json::json_pointer(pointerText);
        } catch (const nlohmann::json::exception&) {
            throw InputError(overrides.origin, pointerText,
                             "expected a JSON pointer such as /render/seed");
        }
        if (pointer.empty() || !json.contains(pointer.parent_pointer()))
            throw InputError(overrides.origin, pointerText,
                             fmt::format("no such place in {}: its parent does not exist", path));
        const nlohmann::json& parent = json.at(pointer.parent_pointer());
        if (parent.is_array()) {
            const std::string& last = pointer.back();
            size_t index = 0;
            auto [end, ec] = std::from_chars(last.data(), last.data() + last.size(), index);
            if (ec != std::errc() || end != last.data() + last.size() || index >= parent.size())
                throw InputError(overrides.origin, pointerText,
                                 fmt::format("no such place in {}: index {} of an array of {}",
                                             path, last, parent.size()));
        } else if (!parent.is_object()) {
            throw InputError(
                overrides.origin, pointerText,
                fmt::format("no such place in {}: its parent is {}", path, jsonTypeName(parent)));
        }
        json[pointer] = value;
    }
}

}  // namespace

SceneOverrides parseSceneOverrides(const std::vector<std::string>& sets) {
    SceneOverrides overrides;
    for (const std::string& set : sets) {
        const size_t eq = set.find('=');
        if (eq == std::string::npos || eq == 0 || set[0] != '/')
            throw InputError("command line", "--set",
                             fmt::format("\"{}\": expected /json/pointer=VALUE, e.g. "
                                         "/render/seed=7 or '/camera/position=[1,2,3]'",
                                         set));
        nlohmann::json value;
        try {
            value = nlohmann::json::parse(set.substr(eq + 1));
        } catch (const nlohmann::json::exception&) {
            value = set.substr(eq + 1);  // a bare word is a string: /materials/0/species=sugi
        }
        overrides.values.emplace_back(set.substr(0, eq), std::move(value));
    }
    return overrides;
}

std::unique_ptr<Scene> loadScene(const std::string& path, const SceneOverrides& overrides) {
    auto scene = std::make_unique<Scene>();
    scene->file = path;
    nlohmann::json json = parseJsonFile(path);
    applyOverrides(json, overrides, path);
    scene->source = json.dump();
    JsonReader root(json, path);
    root.string("description", "");
    if (auto c = root.object("camera"))
        scene->camera = readCamera(*c);
    else
        throw root.error("camera", "missing: {position, look_at, fov}");
    if (auto s = root.object("render")) scene->settings = readSettings(*s);

    for (JsonReader& l : root.objectList("lights")) scene->lights.push_back(readLight(l, *scene));
    int environments = 0;
    for (const Light& l : scene->lights) environments += l.type == LightType::Environment;
    if (environments > 1) throw root.error("lights", "at most one environment light");

    std::map<std::string, uint32_t> materials;
    for (JsonReader& m : root.objectList("materials")) {
        Material material = readMaterial(m, *scene);
        if (materials.count(material.name))
            throw m.error("name", fmt::format("a second material named \"{}\"", material.name));
        materials[material.name] = static_cast<uint32_t>(scene->materials.size());
        scene->materials.push_back(std::move(material));
    }
    int32_t nextLamella = 0;
    for (JsonReader& o : root.objectList("objects"))
        scene->objects.push_back(readObject(o, *scene, materials, nextLamella));
    if (scene->objects.empty()) throw root.error("objects", "the scene has no objects");
    root.finish();
    return scene;
}

}  // namespace nenrin
