#include "renderer/pov/pov_export.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "renderer/bake/baked_grid.h"
#include "renderer/bake/grid_bake.h"
#include "renderer/bake/grid_writers.h"
#include "renderer/parallel_tiles.h"
#include "util/atomic_output.h"
#include "util/input_error.h"
#include "util/memory_budget.h"

namespace nenrin {

namespace {

namespace fs = std::filesystem;

/// Fade distance of exported point lights (m): the fall-off error is (d / D)^2.
constexpr double kPointFadeDistance = 1e-3;

std::string vec(const Vec3& v) { return fmt::format("<{:.9g}, {:.9g}, {:.9g}>", v.x, v.y, v.z); }
std::string rgb(const Rgb& c) { return fmt::format("rgb <{:.9g}, {:.9g}, {:.9g}>", c.r, c.g, c.b); }

std::string matrix(const RigidTransform& t) {
    // POV transforms row vectors: the rows are the images of the axes, then the origin.
    return fmt::format(
        "matrix <{:.12g}, {:.12g}, {:.12g}, {:.12g}, {:.12g}, {:.12g}, {:.12g}, "
        "{:.12g}, {:.12g}, {:.12g}, {:.12g}, {:.12g}>",
        t.x.x, t.x.y, t.x.z, t.y.x, t.y.y, t.y.z, t.z.x, t.z.y, t.z.z, t.origin.x, t.origin.y,
        t.origin.z);
}

std::string safeName(const std::string& name, size_t index) {
    std::string s = fmt::format("object{}_", index);
    for (char c : name) s += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    return s;
}

void objectBounds(const SceneObject& o, Vec3& lo, Vec3& hi) {
    if (o.shape == ShapeType::Box) {
        hi = o.size * 0.5;
        lo = -hi;
        return;
    }
    lo = hi = o.mesh->positions.front();
    for (const Vec3& p : o.mesh->positions) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
}

/// The wood's albedo sampled on a lattice over the object's bounds (object space, cell corners
/// i / (S - 1) as df3 interpolation wants them), each point through its own board's transform.
/// The lattice of an object's df3 volume (no samples yet): `resolution` along its longest side.
BakedGrid objectLattice(const SceneObject& o, int resolution) {
    Vec3 lo, hi;
    objectBounds(o, lo, hi);
    Vec3 size = hi - lo;
    double longest = std::max({size.x, size.y, size.z});
    auto samples = [&](double extent) {
        return std::max(2, static_cast<int>(std::ceil(resolution * extent / longest)));
    };
    BakedGrid g;
    g.width = samples(size.x);
    g.height = samples(size.y);
    g.depth = samples(size.z);
    g.origin = lo;
    g.stepX = {size.x / (g.width - 1), 0, 0};
    g.stepY = {0, size.y / (g.height - 1), 0};
    g.stepZ = {0, 0, size.z / (g.depth - 1)};
    return g;
}

BakedGrid bakeObjectVolume(const SceneObject& o, const WoodShader& shader, int resolution,
                           int threads) {
    BakedGrid g = objectLattice(o, resolution);
    requireMemory(bakeMemoryBytes(g),
                  fmt::format("the df3 volume of object \"{}\" ({} x {} x {} samples at --volume "
                              "{})",
                              o.name, g.width, g.height, g.depth, resolution),
                  "pov");
    g.data.assign(g.sampleCount() * BakedGrid::kChannels, 0);
    parallelTiles(size_t(g.depth), threads, [&](size_t k) {
        std::vector<Vec3> points;
        std::vector<size_t> index;
        // Per board, so each batch stays compact in tree space.
        std::map<const RigidTransform*, std::vector<std::pair<size_t, Vec3>>> groups;
        for (int j = 0; j < g.height; ++j)
            for (int i = 0; i < g.width; ++i) {
                Vec3 p = g.origin + g.stepX * i + g.stepY * j + g.stepZ * double(k);
                const RigidTransform* treeFromObject = &o.treeFromObject;
                if (o.layout)
                    treeFromObject = &o.layout->lamellae[o.layout->lamellaAt(p)].treeFromProduct;
                groups[treeFromObject].push_back(
                    {(size_t(k) * g.height + j) * g.width + i, treeFromObject->point(p)});
            }
        GrowthScratch scratch;
        std::vector<GrowthSample> growth;
        std::vector<WoodSample> out;
        for (auto& [transform, list] : groups) {
            points.clear();
            for (auto& [at, p] : list) points.push_back(p);
            out.resize(points.size());
            shader.evaluate(points, out, scratch, growth);
            for (size_t n = 0; n < list.size(); ++n) {
                float* px = &g.data[list[n].first * BakedGrid::kChannels];
                Rgb c = out[n].coverage > 0 ? out[n].albedo : kBarkAlbedo;
                px[0] = float(c.r);
                px[1] = float(c.g);
                px[2] = float(c.b);
                px[3] = float(out[n].coverage);
                px[4] = float(out[n].T);
                px[5] = float(out[n].knot);
            }
        }
    });
    return g;
}

std::string materialTexture(const Material& m) {
    switch (m.type) {
        case MaterialType::Diffuse:
            return fmt::format("texture {{ pigment {{ {} }} finish {{ ambient 0 diffuse 1 }} }}",
                               rgb(m.colour));
        case MaterialType::Glossy:
            // Approximate: POV's specular highlight for the coat, no Fresnel.
            return fmt::format(
                "texture {{ pigment {{ {} }} finish {{ ambient 0 diffuse 0.96 specular 0.04 "
                "roughness {:.6g} }} }}",
                rgb(m.colour), std::max(1e-4, m.roughness * m.roughness));
        case MaterialType::Metal:
            return fmt::format(
                "texture {{ pigment {{ {} }} finish {{ ambient 0 diffuse 0 specular 1 metallic "
                "roughness {:.6g} reflection {{ {} }} }} }}",
                rgb(m.colour), std::max(1e-4, m.roughness * m.roughness), rgb(m.colour));
        default:
            return "texture { pigment { rgb 0.5 } finish { ambient 0 diffuse 1 } }";
    }
}

/// The scene's header, camera and lights in POV-Ray's language.
std::string povCameraAndLights(const Scene& scene) {
    const RenderSettings& s = scene.settings;
    const CameraSpec& c = scene.camera;
    double aspect = double(s.width) / s.height;
    double hfov = 2 * std::atan(std::tan(0.5 * c.verticalFov) * aspect) * 180 / std::numbers::pi;

    std::string pov = fmt::format(
        "// POV-Ray 3.7 twin of {} written by nenrin {} (docs/povray-bridge.md).\n"
        "// Render: povray scene.ini  (or: povray -D +FE +WT1 +A0.0 +AM2 +R4 -J +W{} +H{} "
        "scene.pov)\n"
        "#version 3.7;\n"
        "global_settings {{ assumed_gamma 1.0 max_trace_level {} }}\n\n"
        "// The scene stays right-handed with +Y up: `right -x` flips POV's handedness.\n"
        "camera {{ perspective location {} look_at {} sky {}\n"
        "         right -x*{:.12g} up y angle {:.12g} }}\n\n",
        scene.file, NENRIN_VERSION, s.width, s.height, std::max(2, s.maxDepth + 1), vec(c.position),
        vec(c.lookAt), vec(c.up), aspect, hfov);
    if (c.apertureRadius > 0)
        pov += "// Note: the thin lens (aperture) is not exported; this is the pinhole view.\n";

    for (const Light& l : scene.lights) {
        switch (l.type) {
            case LightType::Distant:
                pov += fmt::format("light_source {{ {} color {} parallel point_at <0, 0, 0> }}\n",
                                   vec(l.direction * 1e5), rgb(l.power * (1 / std::numbers::pi)));
                break;
            case LightType::Point: {
                double d = kPointFadeDistance;
                pov += fmt::format("light_source {{ {} color {} fade_distance {} fade_power 2 }}\n",
                                   vec(l.position),
                                   rgb(l.power * (1 / (2 * std::numbers::pi * d * d))), d);
                break;
            }
            case LightType::Rect:
                pov += "// A rect light is not exported (POV-Ray would need an area_light).\n";
                break;
            case LightType::Environment:
                pov += fmt::format(
                    "// The environment does not light the POV-Ray twin (that needs radiosity); "
                    "its mean is the background.\nbackground {{ {} }}\n",
                    rgb(l.environment->averageRadiance()));
                break;
        }
    }
    return pov + "\n";
}

/// A triangle mesh as a POV-Ray mesh2 (without its closing brace).
std::string povMesh2(const TriangleMesh& mesh) {
    std::string body = fmt::format("mesh2 {{\n  vertex_vectors {{ {}", mesh.positions.size());
    for (const Vec3& p : mesh.positions) body += ",\n    " + vec(p);
    body += " }\n";
    if (!mesh.normals.empty()) {
        body += fmt::format("  normal_vectors {{ {}", mesh.normals.size());
        for (const Vec3& n : mesh.normals) body += ",\n    " + vec(n);
        body += " }\n";
    }
    if (!mesh.uvs.empty()) {
        body += fmt::format("  uv_vectors {{ {}", mesh.uvs.size());
        for (const auto& uv : mesh.uvs)
            body += fmt::format(",\n    <{:.9g}, {:.9g}>", uv[0], uv[1]);
        body += " }\n";
    }
    body += fmt::format("  face_indices {{ {}", mesh.triangles.size());
    for (const auto& t : mesh.triangles)
        body += fmt::format(",\n    <{}, {}, {}>", t[0], t[1], t[2]);
    return body + " }\n";
}

/// One object (wood baked into df3 volumes beside the scene, added to `written`).
std::string povObject(const SceneObject& o, const Material& m, const std::string& name,
                      const std::string& folder, const PovExportOptions& options,
                      std::vector<std::string>& written) {
    std::string pov;
    std::string texture = materialTexture(m);
    if (m.type == MaterialType::Wood) {
        BakedGrid grid = bakeObjectVolume(o, *m.wood, options.volumeResolution, options.threads);
        std::string base = (fs::path(folder) / (name + ".df3")).string();
        for (const std::string& f : writeDf3(grid, base)) written.push_back(f);
        pov += fmt::format("#include \"{}.inc\"  // declares nenrin_wood in object space\n", name);
        texture = "texture { pigment { nenrin_wood } finish { ambient 0 diffuse 1 } }";
    } else if (m.type == MaterialType::Textured) {
        pov += "// A textured material is exported as its mean grey.\n";
    }
    pov += fmt::format("// {} ({})\n", o.name, o.type);
    if (o.shape == ShapeType::Box)
        return pov + fmt::format("box {{ {}, {}\n  {}\n  {} }}\n\n", vec(o.size * -0.5),
                                 vec(o.size * 0.5), texture, matrix(o.worldFromObject));
    return pov + povMesh2(*o.mesh) +
           fmt::format("  {}\n  {} }}\n\n", texture, matrix(o.worldFromObject));
}

/// Writes `text` to `path` through an atomic output kept in `outputs` (committed together).
void writeText(const std::string& path, const std::string& text, const char* what,
               std::vector<std::unique_ptr<AtomicOutput>>& outputs) {
    outputs.push_back(std::make_unique<AtomicOutput>(path));
    std::ofstream f(outputs.back()->temporaryPath());
    f << text;
    if (!f) throw InputError(path, "output", fmt::format("cannot write the POV-Ray {}", what));
}

}  // namespace

PovOutputSize povOutputSize(const Scene& scene, const PovExportOptions& options) {
    PovOutputSize size;
    for (const SceneObject& o : scene.objects) {
        if (scene.materials[o.material].type != MaterialType::Wood) continue;
        const BakedGrid g = objectLattice(o, options.volumeResolution);
        // R, G, B and knot df3 files: a 6-byte header and 16 bits a sample.
        size.bytes += 4 * (6 + 2 * double(g.width) * g.height * g.depth);
        ++size.volumes;
    }
    return size;
}

std::vector<std::string> exportPovScene(const Scene& scene, const std::string& folder,
                                        const PovExportOptions& options) {
    if (!fs::is_directory(folder))
        throw InputError(folder, "-o", "expected an existing folder for the POV-Ray scene");
    const PovOutputSize size = povOutputSize(scene, options);
    requireOutputSpace(
        size.bytes,
        fmt::format("writing the df3 volumes of {} wood object{} at --volume {}", size.volumes,
                    size.volumes == 1 ? "" : "s", options.volumeResolution),
        folder);
    std::vector<std::string> written;
    std::string pov = povCameraAndLights(scene);
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& o = scene.objects[i];
        pov += povObject(o, scene.materials[o.material], safeName(o.name, i), folder, options,
                         written);
    }

    const RenderSettings& s = scene.settings;
    std::string povPath = (fs::path(folder) / "scene.pov").string();
    std::string iniPath = (fs::path(folder) / "scene.ini").string();
    std::vector<std::unique_ptr<AtomicOutput>> outputs;
    writeText(povPath, pov, "scene", outputs);
    // The deterministic reference settings of docs/design/povray.md.
    writeText(
        iniPath,
        fmt::format("; nenrin's reference settings for scene.pov (docs/povray-bridge.md)\n"
                    "Input_File_Name=scene.pov\nWidth={}\nHeight={}\nOutput_File_Type=E\n"
                    "Antialias=on\nAntialias_Threshold=0.0\nSampling_Method=2\nAntialias_Depth=4\n"
                    "Jitter=off\nDisplay=off\n",
                    s.width, s.height),
        "ini file", outputs);
    for (auto& o : outputs) o->commit();
    written.push_back(povPath);
    written.push_back(iniPath);
    return written;
}

}  // namespace nenrin
