#include "renderer/path_tracer.h"

#include <fmt/format.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "renderer/adaptive_sampling.h"
#include "renderer/camera.h"
#include "renderer/direct_light.h"
#include "renderer/film_tile.h"
#include "renderer/lights.h"
#include "renderer/material_bsdf.h"
#include "renderer/parallel_tiles.h"
#include "renderer/ray_scene.h"
#include "renderer/sample_dimensions.h"
#include "shader/surface_bsdf.h"
#include "util/axis_frame.h"
#include "util/memory_budget.h"
#include "util/progress.h"

namespace nenrin {

namespace {

constexpr int kTileSize = kRenderTileSize;
/// A pixel whose shared wood evaluation is on a knot's edge (knot share between this and
/// 1 - this) is shaded per sample.
constexpr double kKnotRefinement = 0.02;
constexpr uint32_t kSamplesPerPass = 64;
constexpr double kRegularisedRoughness = 0.3;

double maxComponent(const Rgb& c) { return std::max(c.r, std::max(c.g, c.b)); }
bool isBlack(const Rgb& c) { return c.r <= 0 && c.g <= 0 && c.b <= 0; }

/// Share of a footprint of diameter `footprint` centred `distance` from the middle of a line
/// of `width`: the box-filtered glue line, so it neither aliases nor vanishes far away.
double glueCoverage(double distance, double width, double footprint) {
    if (footprint <= 1e-3 * width) return distance <= 0.5 * width ? 1 : 0;
    double overlap = std::min(distance + 0.5 * width, 0.5 * footprint) -
                     std::max(distance - 0.5 * width, -0.5 * footprint);
    return std::clamp(overlap / footprint, 0.0, 1.0);
}

struct PathState {
    Ray ray;
    /// Film position of the camera sample (pixels): its ray differentials are made again
    /// from it where a footprint is needed, instead of being carried by every path.
    double filmX = 0, filmY = 0;
    Rgb throughput{1, 1, 1};
    Rgb radiance;
    uint32_t pixel = 0;  ///< index within the tile
    uint32_t sample = 0;
    int depth = 0;
    double bsdfPdf = 0;  ///< density of the bounce that made the current ray (for MIS)
    /// The vertex the current ray left and its geometric normal: where a light the ray finds
    /// would have been selected from (MIS with light selection).
    Vec3 lastPosition, lastNormal;
    bool alive = true;
    SurfaceHit hit;
    // Shading inputs worked out per hit.
    uint32_t material = 0;
    int32_t lamella = -1;
    Rgb boardTint{1, 1, 1};  ///< the board's tree (cut plan)
    const RigidTransform* treeFromObject = nullptr;
    const RigidTransform* worldFromObject = nullptr;
    const GlueLine* glue = nullptr;  ///< laminated products
    double glueDistance = 0;         ///< m, to the nearest glued boundary
    double glueCover = 0;            ///< share of the footprint on the glue line
    /// Path regularisation: after a diffuse bounce, glossy lobes are at least this rough, so
    /// sun glints seen through diffuse bounces (caustics) blur instead of sparkling.
    double minRoughness = 0;
};

class TileRenderer {
public:
    TileRenderer(const Scene& scene, const RayScene& rays, const Camera& camera)
        : scene_(scene), rays_(rays), camera_(camera), directLight_(scene) {}

    void render(int x0, int y0, int x1, int y1, Film& film, RenderStats& stats);

private:
    void traceCamera(std::vector<PathState>& paths);
    void resolveHits(std::vector<PathState>& paths, TileAovs& aovs,
                     const std::vector<uint64_t>& pixelIds);
    void shadeWood(std::vector<PathState>& paths, const std::vector<uint32_t>& woodPaths);
    /// The camera ray of a path's sample, with its differentials.
    CameraRay cameraRay(const PathState& path, uint64_t pixelId) const {
        auto [lu, lv] = lensSample(path, pixelId);
        return camera_.generate(path.filmX, path.filmY, lu, lv, differentialScale_);
    }
    /// The sample's point on the lens (a pinhole needs none).
    std::pair<double, double> lensSample(const PathState& path, uint64_t pixelId) const {
        if (!camera_.hasLens()) return {0, 0};
        const uint64_t seed = scene_.settings.seed;
        return pairAt(seed, pixelId, path.sample, dimension::kLens);
    }
    /// Fills groupResults_ (one per pixel) and groupStart_ for a camera batch of n entries.
    void shadeCameraWood(const WoodShader& shader, size_t n);
    void shade(uint32_t index, PathState& path, uint64_t pixelId, const WoodSurfaceSample* wood,
               TileAovs& aovs);
    void traceShadows(std::vector<PathState>& paths, TileAovs& aovs);

    const Scene& scene_;
    const RayScene& rays_;
    const Camera& camera_;
    DirectLight directLight_;
    uint64_t rayCount_ = 0;
    // Scratch, reused by the tiles one thread renders (no allocation per tile).
    std::vector<PathState> paths_;
    std::vector<ShadowRay> shadows_;  ///< this bounce's light samples, in path order
    /// The shading state shared by the camera samples of one pixel and board face (shade).
    struct SharedSurface {
        const WoodSurfaceSample* wood = nullptr;
        Vec3 ng;
        SurfaceShading surface;
        std::vector<Rgb> lightValue;  ///< BSDF value towards each distant light; r < 0: unknown
    } shared_;
    std::vector<uint8_t> finished_;  ///< paths that ended this bounce
    TileSampling sampling_;          ///< how many samples each pixel of the tile takes
    std::vector<uint64_t> pixelIds_;
    std::vector<double> rotations_;
    std::vector<uint32_t> woodPathIds_, woodOrder_;
    std::vector<WoodSurfaceSample> woodResults_;
    std::vector<int32_t> woodSlot_;
    WoodScratch woodScratch_;
    std::vector<Vec3> woodPoints_;
    std::vector<SurfaceFootprint> woodFootprints_;
    std::vector<WoodSurfaceSample> woodBatch_;
    std::vector<WoodSample> woodPlain_;
    // Camera hits shaded once per pixel and board (shadeCameraWood).
    std::vector<uint32_t> groupStart_;
    std::vector<Vec3> groupPoints_;
    std::vector<SurfaceFootprint> groupFootprints_;
    std::vector<WoodSurfaceSample> groupResults_;
    std::vector<uint32_t> batchPixel_;
    std::vector<int32_t> refineEntries_;  ///< per batch entry: its quadrant evaluation, or -1
    std::vector<int32_t> refineSlots_;
    std::vector<Vec3> refinePoints_;
    std::vector<SurfaceFootprint> refineFootprints_;
    std::vector<WoodSurfaceSample> refineResults_;
    double differentialScale_ = 1;
};

void TileRenderer::render(int x0, int y0, int x1, int y1, Film& film, RenderStats& stats) {
    const RenderSettings& settings = scene_.settings;
    const int tw = x1 - x0, th = y1 - y0;
    const size_t pixels = size_t(tw) * th;
    const uint32_t spp = static_cast<uint32_t>(settings.spp);
    differentialScale_ = std::max(0.125, 1 / std::sqrt(double(spp)));

    rayCount_ = 0;
    std::vector<uint64_t>& pixelIds = pixelIds_;
    std::vector<double>& rotations = rotations_;
    pixelIds.resize(pixels);
    rotations.resize(2 * pixels);
    for (int j = 0; j < th; ++j) {
        for (int i = 0; i < tw; ++i) {
            uint32_t p = static_cast<uint32_t>(j * tw + i);
            uint64_t id = uint64_t(y0 + j) * settings.width + (x0 + i);
            pixelIds[p] = id;
            // Pixel jitter: the R2 sequence over the samples, rotated per pixel.
            rotations[2 * p] =
                randomAt(settings.seed, id, dimension::kPixelSample, dimension::kJitterRotationX);
            rotations[2 * p + 1] =
                randomAt(settings.seed, id, dimension::kPixelSample, dimension::kJitterRotationY);
        }
    }

    TileAovs aovs(pixels);
    sampling_.start(tw, th, settings);
    const std::vector<uint32_t>& done = sampling_.samplesDone();
    const std::vector<uint32_t>& target = sampling_.samplesTarget();
    std::vector<PathState>& paths = paths_;
    // Rounds of samples (one without adaptive sampling), each in passes of at most
    // kSamplesPerPass samples per pixel, which bounds memory at any spp; each pixel still adds
    // its samples in order, so sums are deterministic.
    while (const uint32_t longest = sampling_.longestRound()) {
        for (uint32_t k0 = 0; k0 < longest; k0 += kSamplesPerPass) {
            size_t count = 0;
            for (size_t p = 0; p < pixels; ++p)
                count += std::min(target[p] - done[p] - std::min(target[p] - done[p], k0),
                                  kSamplesPerPass);
            // Only the fields a new camera path needs are reset: the state is large, and
            // resetting all of it for every sample was a measurable share of a render.
            paths.resize(count);
            size_t next = 0;
            for (int j = 0; j < th; ++j) {
                for (int i = 0; i < tw; ++i) {
                    uint32_t p = static_cast<uint32_t>(j * tw + i);
                    uint64_t id = pixelIds[p];
                    const uint32_t s0 = done[p] + k0;
                    const uint32_t s1 = std::min(target[p], s0 + kSamplesPerPass);
                    for (uint32_t s = s0; s < s1; ++s) {
                        PathState& path = paths[next++];
                        path.throughput = {1, 1, 1};
                        path.radiance = {};
                        path.depth = 0;
                        path.bsdfPdf = 0;
                        path.alive = true;
                        path.minRoughness = 0;
                        path.glue = nullptr;
                        path.pixel = p;
                        path.sample = s;
                        double jx = rotations[2 * p] + s * 0.7548776662466927;
                        double jy = rotations[2 * p + 1] + s * 0.5698402909980532;
                        jx -= std::floor(jx);
                        jy -= std::floor(jy);
                        path.filmX = x0 + i + jx;
                        path.filmY = y0 + j + jy;
                        auto [lu, lv] = lensSample(path, id);
                        path.ray = camera_.primary(path.filmX, path.filmY, lu, lv);
                    }
                }
            }
            traceCamera(paths);
            while (true) {
                resolveHits(paths, aovs, pixelIds);
                bool any = false;
                for (PathState& path : paths) {
                    if (!path.alive) continue;
                    any = true;
                    path.hit = rays_.intersect(path.ray);
                    ++rayCount_;
                }
                if (!any) break;
            }
        }
        sampling_.endRound(aovs.rgb);
    }

    aovs.writeInto(film, x0, y0, tw, th, done);
    for (size_t p = 0; p < pixels; ++p) stats.cameraRays += done[p];
    stats.rays += rayCount_;
}

void TileRenderer::traceCamera(std::vector<PathState>& paths) {
    Ray rays[16];
    SurfaceHit hits[16];
    for (size_t base = 0; base < paths.size(); base += 16) {
        int count = static_cast<int>(std::min<size_t>(16, paths.size() - base));
        for (int k = 0; k < count; ++k) rays[k] = paths[base + k].ray;
        rays_.intersect16(rays, count, hits);
        for (int k = 0; k < count; ++k) paths[base + k].hit = hits[k];
    }
    rayCount_ += paths.size();
}

/// Surface points of the hits: where in the tree (wood), which board, and the footprint.
void TileRenderer::resolveHits(std::vector<PathState>& paths, TileAovs& aovs,
                               const std::vector<uint64_t>& pixelIds) {
    std::vector<uint32_t>& woodPaths = woodPathIds_;
    woodPaths.clear();
    for (uint32_t i = 0; i < paths.size(); ++i) {
        PathState& path = paths[i];
        if (!path.alive || !path.hit.hit || path.hit.isLight) continue;
        const SceneObject& object = scene_.objects[path.hit.index];
        path.material = object.material;
        path.worldFromObject = &object.worldFromObject;
        path.lamella = -1;
        path.boardTint = {1, 1, 1};
        path.treeFromObject = &object.treeFromObject;
        path.glue = nullptr;
        if (object.layout) {
            Vec3 local = object.worldFromObject.inverse().point(path.hit.position);
            const Lamella& l = object.layout->lamellae[object.layout->lamellaAt(local)];
            path.lamella = l.id;
            path.boardTint = l.tint;
            path.treeFromObject = &l.treeFromProduct;
            if (object.layout->glue.width > 0) {
                path.glue = &object.layout->glue;
                path.glueDistance = object.layout->glueDistance(local);
            }
        }
        if (scene_.materials[path.material].type == MaterialType::Wood) woodPaths.push_back(i);
    }
    shadeWood(paths, woodPaths);
    shared_.wood = nullptr;  // results of earlier bounces may reuse these addresses
    shadows_.clear();
    finished_.assign(paths.size(), 0);
    for (uint32_t i = 0; i < paths.size(); ++i) {
        PathState& path = paths[i];
        if (!path.alive) continue;
        const WoodSurfaceSample* wood = woodSlot_[i] >= 0 ? &woodResults_[woodSlot_[i]] : nullptr;
        shade(i, path, pixelIds[path.pixel], wood, aovs);
    }
    traceShadows(paths, aovs);
}

/// The light samples of this bounce, in 16-ray packets; then, in path order, each path gets its
/// unoccluded contributions (in light order) and finished paths go into the film: the same
/// sums in the same order as tracing each shadow ray where it was made.
void TileRenderer::traceShadows(std::vector<PathState>& paths, TileAovs& aovs) {
    traceShadowRays(rays_, shadows_);
    rayCount_ += shadows_.size();
    size_t next = 0;
    for (uint32_t i = 0; i < paths.size(); ++i) {
        PathState& path = paths[i];
        for (; next < shadows_.size() && shadows_[next].path == i; ++next)
            if (!shadows_[next].blocked)
                path.radiance = path.radiance + shadows_[next].contribution;
        if (!finished_[i]) continue;
        aovs.rgb[path.pixel] = aovs.rgb[path.pixel] + path.radiance;
        sampling_.addSample(path.pixel, path.sample, path.radiance);
    }
}

void TileRenderer::shadeWood(std::vector<PathState>& paths,
                             const std::vector<uint32_t>& woodPaths) {
    woodSlot_.assign(paths.size(), -1);
    woodResults_.clear();
    // Coherent batches: by material, then board, then path order (pixel-major).
    std::vector<uint32_t>& order = woodOrder_;
    order.resize(woodPaths.size());
    std::iota(order.begin(), order.end(), 0u);
    auto before = [&](uint32_t a, uint32_t b) {
        const PathState& pa = paths[woodPaths[a]];
        const PathState& pb = paths[woodPaths[b]];
        if (pa.material != pb.material) return pa.material < pb.material;
        return pa.treeFromObject < pb.treeFromObject;
    };
    // Often one board fills the tile: then the order is already right.
    if (!std::is_sorted(order.begin(), order.end(), before))
        std::stable_sort(order.begin(), order.end(), before);
    size_t begin = 0;
    while (begin < order.size()) {
        const PathState& first = paths[woodPaths[order[begin]]];
        size_t end = begin + 1;
        while (end < order.size()) {
            const PathState& p = paths[woodPaths[order[end]]];
            if (p.material != first.material || p.treeFromObject != first.treeFromObject) break;
            ++end;
        }
        const WoodShader& shader = *scene_.materials[first.material].wood;
        const RigidTransform treeFromWorld =
            (*first.treeFromObject) * first.worldFromObject->inverse();
        const bool camera = first.depth == 0;
        size_t n = end - begin;
        woodPoints_.resize(n);
        woodFootprints_.resize(camera ? n : 0);
        batchPixel_.resize(n);
        // A camera sample's footprint: where the neighbouring pixels' rays (scaled to the
        // sample's share of the pixel) meet the hit's plane.
        auto footprintOf = [&](size_t k) -> SurfaceFootprint {
            const PathState& p = paths[woodPaths[order[begin + k]]];
            const Vec3& n0 = p.hit.geometricNormal;
            auto onPlane = [&](const Ray& r) {
                double den = dot(n0, r.direction);
                if (std::abs(den) < 1e-12) return p.hit.position;
                double t = dot(n0, p.hit.position - r.origin) / den;
                return r.origin + r.direction * t;
            };
            CameraRay c = cameraRay(p, pixelIds_[p.pixel]);
            return {treeFromWorld.vector(onPlane(c.rayX) - p.hit.position),
                    treeFromWorld.vector(onPlane(c.rayY) - p.hit.position), 0,
                    treeFromWorld.vector(n0)};
        };
        for (size_t k = 0; k < n; ++k) {
            const PathState& p = paths[woodPaths[order[begin + k]]];
            batchPixel_[k] = p.pixel;
            woodPoints_[k] = treeFromWorld.point(p.hit.position);
            // Footprints for the first sample of each pixel (shadeCameraWood) and for samples
            // near glue lines.
            if (camera && (k == 0 || batchPixel_[k] != batchPixel_[k - 1] || p.glue))
                woodFootprints_[k] = footprintOf(k);
        }
        woodBatch_.resize(n);
        if (camera) {
            shadeCameraWood(shader, n);
            // Knots are not prefiltered: a knot's rim would alias if a whole pixel took one
            // evaluation, so pixels on a knot's edge are shaded per quarter pixel: each sample
            // takes the evaluation of its quadrant (centroid, half-pixel footprint).
            refineEntries_.assign(n, -1);
            refinePoints_.clear();
            refineFootprints_.clear();
            const double half = 0.5 / differentialScale_;
            for (size_t g = 0; g + 1 < groupStart_.size(); ++g) {
                const double knot = groupResults_[g].knot;
                const uint32_t g0 = groupStart_[g], g1 = groupStart_[g + 1];
                if (knot <= kKnotRefinement || knot >= 1 - kKnotRefinement || g1 - g0 < 2) continue;
                int32_t slotOfQuadrant[4] = {-1, -1, -1, -1};
                uint32_t count[4] = {0, 0, 0, 0};
                for (uint32_t k = g0; k < g1; ++k) {
                    const PathState& p = paths[woodPaths[order[begin + k]]];
                    int q = (p.filmX - std::floor(p.filmX) >= 0.5) +
                            2 * (p.filmY - std::floor(p.filmY) >= 0.5);
                    if (slotOfQuadrant[q] < 0) {
                        slotOfQuadrant[q] = static_cast<int32_t>(refinePoints_.size());
                        refinePoints_.push_back({0, 0, 0});
                        refineFootprints_.push_back({woodFootprints_[g0].dpdx * half,
                                                     woodFootprints_[g0].dpdy * half, 0,
                                                     woodFootprints_[g0].normal});
                    }
                    Vec3& sum = refinePoints_[static_cast<size_t>(slotOfQuadrant[q])];
                    sum = sum + woodPoints_[k];
                    ++count[q];
                    refineEntries_[k] = slotOfQuadrant[q];
                }
                for (int q = 0; q < 4; ++q)
                    if (count[q] > 0) {
                        Vec3& sum = refinePoints_[static_cast<size_t>(slotOfQuadrant[q])];
                        sum = sum * (1.0 / count[q]);
                    }
            }
            refineResults_.resize(refinePoints_.size());
            if (!refinePoints_.empty())
                shader.evaluateSurface(refinePoints_, refineFootprints_, refineResults_,
                                       woodScratch_);
        } else {
            woodPlain_.resize(n);
            shader.evaluate(woodPoints_, woodPlain_, woodScratch_.growth, woodScratch_.samples);
            for (size_t k = 0; k < n; ++k) {
                WoodSurfaceSample& w = woodBatch_[k];
                w = WoodSurfaceSample{};
                w.albedo = woodPlain_[k].albedo;
                w.coverage = woodPlain_[k].coverage;
                w.T = woodPlain_[k].T;
                w.knot = woodPlain_[k].knot;
            }
        }
        const RigidTransform worldFromTree = treeFromWorld.inverse();
        for (size_t k = 0; k < n; ++k) {
            PathState& p = paths[woodPaths[order[begin + k]]];
            if (p.glue) {
                double footprint = 0;
                if (camera)
                    footprint = std::sqrt(std::max(lengthSquared(woodFootprints_[k].dpdx),
                                                   lengthSquared(woodFootprints_[k].dpdy)));
                p.glueCover = glueCoverage(p.glueDistance, p.glue->width, footprint);
            }
        }
        // Results in world space (directions back from tree space), one per camera pixel
        // group or per indirect hit; each path points at its result.
        auto keep = [&](WoodSurfaceSample w) {
            w.fibre = worldFromTree.vector(w.fibre);
            w.reliefGradient = worldFromTree.vector(w.reliefGradient);
            woodResults_.push_back(w);
            return static_cast<int32_t>(woodResults_.size() - 1);
        };
        if (camera) {
            // Quadrant results first, so each is kept once.
            refineSlots_.resize(refineResults_.size());
            for (size_t r = 0; r < refineResults_.size(); ++r)
                refineSlots_[r] = keep(refineResults_[r]);
            for (size_t g = 0; g + 1 < groupStart_.size(); ++g) {
                const uint32_t g0 = groupStart_[g], g1 = groupStart_[g + 1];
                const bool refined = refineEntries_[g0] >= 0;
                int32_t slot = refined ? -1 : keep(groupResults_[g]);
                for (uint32_t k = g0; k < g1; ++k)
                    woodSlot_[woodPaths[order[begin + k]]] =
                        refined ? refineSlots_[static_cast<size_t>(refineEntries_[k])] : slot;
            }
        } else {
            for (size_t k = 0; k < n; ++k)
                woodSlot_[woodPaths[order[begin + k]]] = keep(woodBatch_[k]);
        }
        begin = end;
    }
}

/// The wood seen by camera samples is shaded once per pixel and board: at the mean of the
/// samples' tree-space points, filtered over the whole pixel's footprint (the per-sample
/// differentials are 1 / differentialScale_ shorter). The ring profile is prefiltered over
/// that footprint, so this is the pixel's box-filtered wood, as the mean of the samples' own
/// (smaller-footprint) evaluations would be, at 1/spp of the cost. Light, visibility and
/// geometry stay sampled per sample. Batch entries of one pixel are adjacent (pixel-major).
void TileRenderer::shadeCameraWood(const WoodShader& shader, size_t n) {
    groupStart_.clear();
    groupPoints_.clear();
    groupFootprints_.clear();
    const double widen = 1 / differentialScale_;
    for (size_t k = 0; k < n; ++k) {
        if (k == 0 || batchPixel_[k] != batchPixel_[k - 1]) {
            groupStart_.push_back(static_cast<uint32_t>(k));
            groupPoints_.push_back({0, 0, 0});
            groupFootprints_.push_back({woodFootprints_[k].dpdx * widen,
                                        woodFootprints_[k].dpdy * widen, 0,
                                        woodFootprints_[k].normal});
        }
        groupPoints_.back() = groupPoints_.back() + woodPoints_[k];
    }
    groupStart_.push_back(static_cast<uint32_t>(n));
    const size_t groups = groupPoints_.size();
    for (size_t g = 0; g < groups; ++g)
        groupPoints_[g] = groupPoints_[g] * (1.0 / (groupStart_[g + 1] - groupStart_[g]));
    groupResults_.resize(groups);
    shader.evaluateSurface(groupPoints_, groupFootprints_, groupResults_, woodScratch_);
}

void TileRenderer::shade(uint32_t index, PathState& path, uint64_t pixelId,
                         const WoodSurfaceSample* wood, TileAovs& aovs) {
    const RenderSettings& settings = scene_.settings;
    const BounceRandom rnd(settings.seed, pixelId, path.sample, path.depth);
    const Vec3 wo = -path.ray.direction;
    const bool camera = path.depth == 0;

    if (!path.hit.hit || path.hit.isLight) {
        Rgb le;
        double lightPdf = 0;
        if (!path.hit.hit) {
            le = directLight_.environmentRadiance(path.ray.direction);
            if (!camera)
                lightPdf = directLight_.environmentPdf(path.ray.direction, path.lastPosition,
                                                       path.lastNormal);
        } else {
            const Light& l = scene_.lights[path.hit.index];
            le = rectLightRadiance(l, path.ray.direction);
            if (!camera)
                lightPdf =
                    directLight_.rectPdf(path.hit.index, path.ray.direction, path.hit.distance,
                                         path.lastPosition, path.lastNormal);
            if (camera)
                aovs.addEmitterHit(path.pixel,
                                   path.hit.distance * dot(path.ray.direction, camera_.forward()),
                                   path.hit.geometricNormal);
        }
        double w = camera ? 1 : powerHeuristic(path.bsdfPdf, lightPdf);
        path.radiance = path.radiance + multiply(path.throughput, le) * w;
        path.alive = false;
        finished_[index] = 1;
        return;
    }

    // The surface: normals facing the incoming ray.
    const Material& material = scene_.materials[path.material];
    Vec3 ng = path.hit.geometricNormal;
    Vec3 ns = path.hit.shadingNormal;
    if (dot(ng, wo) < 0) ng = -ng;
    if (dot(ns, ng) < 0) ns = -ns;

    // Camera samples of one pixel that see the same board face share its shading state: the
    // wood was evaluated once for them (shadeCameraWood), so the layered BSDF, the bumped normal
    // and the frame are the same; so is the BSDF's value towards a distant light, up to the
    // pixel's spread of view directions. Each sample keeps its own light sample and shadow ray.
    const bool shareable = camera && material.type == MaterialType::Wood && wood != nullptr &&
                           !(path.glue && path.glueCover > 0);
    const bool reuse = shareable && shared_.wood == wood && shared_.ng == ng;
    SurfaceShading surface;
    if (reuse) {
        surface = shared_.surface;
    } else {
        surface = materialBsdf(material, {&path.hit, wo, ns, wood, path.boardTint, path.glue,
                                          path.glueCover, path.minRoughness});
        if (shareable) {
            shared_.wood = wood;
            shared_.ng = ng;
            shared_.surface = surface;
            shared_.lightValue.assign(scene_.lights.size(), Rgb{-1, -1, -1});
        }
    }
    const SurfaceBsdf& bsdf = surface.bsdf;
    const AxisFrame& frame = surface.frame;
    ns = surface.ns;
    const Vec3 woLocal = frame.toLocal(wo);

    if (camera) {
        aovs.addSurfaceHit(path.pixel, bsdf.base, ns,
                           path.hit.distance * dot(path.ray.direction, camera_.forward()));
        if (wood) aovs.addWoodHit(path.pixel, wood->T, wood->knot);
        if (path.sample == 0) aovs.lamella[path.pixel] = path.lamella;
    }

    // Next-event estimation: its shadow rays are traced with the others of this bounce.
    directLight_.sample({path.hit.position, ng, &surface, woLocal, path.throughput,
                         path.depth + 1 < settings.maxDepth},
                        rnd, shareable ? std::span<Rgb>(shared_.lightValue) : std::span<Rgb>(),
                        index, shadows_);

    // Continue the path.
    SurfaceBsdf::Sample bs;
    bool more = path.depth + 1 < settings.maxDepth && [&] {
        const auto [u, v] = rnd.pair(dimension::kBsdfDirection);
        return bsdf.sample(woLocal, rnd.at(dimension::kBsdfLobe), u, v, bs);
    }();
    Vec3 wi = more ? frame.toWorld(bs.wi) : Vec3{};
    if (more && dot(wi, ng) <= 0) more = false;
    if (more) {
        path.throughput = multiply(path.throughput, bs.weight);
        if (path.depth >= 2) {
            double q = std::min(0.95, maxComponent(path.throughput));
            if (rnd.at(dimension::kRoulette) >= q)
                more = false;
            else
                path.throughput = path.throughput * (1 / q);
        }
    }
    if (!more || isBlack(path.throughput)) {
        path.alive = false;
        finished_[index] = 1;
        return;
    }
    path.bsdfPdf = bs.pdf;
    path.lastPosition = path.hit.position;
    path.lastNormal = ng;
    if (bs.roughness >= 1) path.minRoughness = kRegularisedRoughness;
    path.ray = {offsetOrigin(path.hit.position, ng, wi), wi};
    ++path.depth;
}

}  // namespace

Film renderScene(const Scene& scene, const RenderOptions& options, RenderStats& stats) {
    const RenderSettings& settings = scene.settings;
    auto start = std::chrono::steady_clock::now();
    RayScene rays(scene);
    Camera camera(scene.camera, settings.width, settings.height);
    const int rowEnd = options.rows.end < 0 ? settings.height : options.rows.end;
    if (options.rows.begin % kTileSize != 0 || options.rows.begin < 0 ||
        rowEnd <= options.rows.begin || rowEnd > settings.height ||
        (rowEnd % kTileSize != 0 && rowEnd != settings.height))
        throw std::invalid_argument("renderScene: rows not a band of whole tile rows");
    // Film channels, the per-pixel sampling state and the EXR writer's copy: ~160 bytes a pixel.
    requireMemory(160.0 * settings.width * (rowEnd - options.rows.begin),
                  fmt::format("a {}x{} frame", settings.width, rowEnd - options.rows.begin),
                  scene.file);
    Film film;
    film.resize(settings.width, settings.height, options.rows.begin, rowEnd - options.rows.begin);
    if (settings.noiseThreshold > 0) film.samples.assign(film.alpha.size(), 0);

    const int tilesX = (settings.width + kTileSize - 1) / kTileSize;
    const int firstTileRow = options.rows.begin / kTileSize;
    const int tilesY = (rowEnd + kTileSize - 1) / kTileSize - firstTileRow;
    const size_t tileCount = size_t(tilesX) * tilesY;
    std::vector<RenderStats> tileStats(tileCount);
    ProgressReporter progress(static_cast<long long>(tileCount), "Rendering", options.quiet);
    // One renderer per thread: its buffers serve all the tiles the thread renders.
    tbb::enumerable_thread_specific<TileRenderer> renderers(
        [&] { return TileRenderer(scene, rays, camera); });
    parallelTiles(tileCount, options.threads, [&](size_t tile) {
        int tx = static_cast<int>(tile % tilesX),
            ty = firstTileRow + static_cast<int>(tile / tilesX);
        int x0 = tx * kTileSize, y0 = ty * kTileSize;
        int x1 = std::min(settings.width, x0 + kTileSize);
        int y1 = std::min(settings.height, y0 + kTileSize);
        renderers.local().render(x0, y0, x1, y1, film, tileStats[tile]);
        progress.advance();
    });
    progress.done();
    stats = {};
    for (const RenderStats& s : tileStats) {
        stats.cameraRays += s.cameraRays;
        stats.rays += s.rays;
    }
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return film;
}

}  // namespace nenrin
