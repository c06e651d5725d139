#include "renderer/path_tracer.h"

#include <fmt/format.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <span>
#include <stdexcept>
#include <vector>

#include "renderer/adaptive_sampling.h"
#include "renderer/camera.h"
#include "renderer/direct_light.h"
#include "renderer/film_tile.h"
#include "renderer/lights.h"
#include "renderer/material_bsdf.h"
#include "renderer/parallel_tiles.h"
#include "renderer/path_state.h"
#include "renderer/ray_scene.h"
#include "renderer/sample_dimensions.h"
#include "renderer/wood_hits.h"
#include "shader/surface_bsdf.h"
#include "util/axis_frame.h"
#include "util/memory_budget.h"
#include "util/progress.h"

namespace nenrin {

namespace {

constexpr int kTileSize = kRenderTileSize;
constexpr uint32_t kSamplesPerPass = 64;
/// A pass's pixels are taken in groups of about this many paths: each path's state (~500
/// bytes) is read and written by every step of a bounce, and a tile's 4096 paths at 16 spp
/// (2 MB) did not stay in the cache between the steps.
constexpr size_t kPathsPerGroup = 1024;
constexpr double kRegularisedRoughness = 0.3;

double maxComponent(const Rgb& c) { return std::max(c.r, std::max(c.g, c.b)); }

/// part / whole per channel (0 where whole is 0).
Rgb share(const Rgb& part, const Rgb& whole) {
    auto ratio = [](double p, double w) { return w > 0 ? p / w : 0.0; };
    return {ratio(part.r, whole.r), ratio(part.g, whole.g), ratio(part.b, whole.b)};
}

/// The shading state shared by the camera samples of one pixel that see one board face: the
/// wood was evaluated once for them (WoodHits), so the layered BSDF, the bumped normal and the
/// frame are the same; so is the BSDF's value towards a distant light, up to the pixel's spread
/// of view directions. Each sample keeps its own light sample and shadow ray. Keyed on the wood
/// evaluation, which never matches one of an earlier bounce, and on the face's normal.
class SharedSurface {
public:
    /// The shading kept for (wood, ng), or null.
    const SurfaceShading* find(const WoodHits::Evaluation& wood, const Vec3& ng) const {
        return wood_ == wood && ng_ == ng ? &surface_ : nullptr;
    }
    /// Keeps `surface` for (wood, ng), with no BSDF values known yet towards the `lights`.
    void keep(const WoodHits::Evaluation& wood, const Vec3& ng, const SurfaceShading& surface,
              size_t lights) {
        wood_ = wood;
        ng_ = ng;
        surface_ = surface;
        lightValue_.assign(
            lights,
            BsdfValue{
                .f = {-1, -1, -1}, .diffuse = {}, .lit = false, .litF = {}, .litDiffuse = {}});
    }
    /// The BSDF's value towards each light (kept for the distant ones); f.r < 0: not known yet.
    std::span<BsdfValue> lightValues() { return lightValue_; }

private:
    WoodHits::Evaluation wood_;
    Vec3 ng_;
    SurfaceShading surface_;
    std::vector<BsdfValue> lightValue_;
};

/// Renders tiles: one per thread, its buffers serving every tile the thread renders (no
/// allocation per tile).
class TileRenderer {
public:
    TileRenderer(const Scene& scene, const RayScene& rays, const Camera& camera)
        : scene_(scene),
          rays_(rays),
          camera_(camera),
          cameraSampler_(camera, scene.settings),
          directLight_(scene),
          woodHits_(scene, cameraSampler_) {}

    void render(int x0, int y0, int x1, int y1, Film& film, RenderStats& stats);

private:
    void startTile(int x0, int y0, int x1, int y1);
    void startCameraPaths(uint32_t k0, uint32_t pixelBegin, uint32_t pixelEnd);
    uint32_t groupEnd(uint32_t k0, uint32_t pixelBegin) const;
    uint32_t samplesInPass(uint32_t pixel, uint32_t k0) const;
    void traceCamera();
    void shadeBounce(TileAovs& aovs);
    void locateBoards();
    void shade(uint32_t index, PathState& path, TileAovs& aovs);
    void addEmission(PathState& path, TileAovs& aovs) const;
    bool bounce(PathState& path, const SurfaceShading& surface, const Vec3& ng, const Vec3& woLocal,
                const BounceRandom& random) const;
    void finish(uint32_t index, PathState& path) {
        path.alive = false;
        finished_[index] = 1;
    }
    void traceShadows(TileAovs& aovs);
    bool traceContinuing();

    const Scene& scene_;
    const RayScene& rays_;
    const Camera& camera_;
    CameraSampler cameraSampler_;
    DirectLight directLight_;
    WoodHits woodHits_;
    // The tile being rendered.
    int x0_ = 0, y0_ = 0, tw_ = 0, th_ = 0;
    std::vector<uint64_t> pixelKeys_;  ///< per pixel of the tile: its random numbers' key
    std::vector<double> rotations_;    ///< per pixel of the tile: its jitter rotation (x, y)
    TileSampling sampling_;            ///< how many samples each pixel of the tile takes
    uint64_t rayCount_ = 0;
    // The pass: its paths, and what their current bounce found.
    std::vector<PathState> paths_;
    std::vector<uint32_t> woodPaths_;  ///< the paths on wood
    std::vector<ShadowRay> shadows_;   ///< the light samples, in path order
    std::vector<uint8_t> finished_;    ///< the paths that ended
    SharedSurface shared_;             ///< camera samples' shading, shared per pixel and board face
    /// A vertex's own shading where it shares none: a member, not a local, because a local
    /// std::optional of it was cleared (232 bytes, rep stos) at every vertex.
    SurfaceShading ownShading_;
};

void TileRenderer::render(int x0, int y0, int x1, int y1, Film& film, RenderStats& stats) {
    startTile(x0, y0, x1, y1);
    TileAovs aovs(pixelKeys_.size());
    sampling_.start(tw_, th_, scene_.settings);
    // Rounds of samples (one without adaptive sampling), each in passes of at most
    // kSamplesPerPass samples per pixel, which bounds memory at any spp; each pixel still adds
    // its samples in order, so sums are deterministic.
    while (const uint32_t longest = sampling_.longestRound()) {
        const uint32_t pixels = static_cast<uint32_t>(pixelKeys_.size());
        for (uint32_t k0 = 0; k0 < longest; k0 += kSamplesPerPass)
            for (uint32_t p0 = 0, p1 = 0; p0 < pixels; p0 = p1) {
                p1 = groupEnd(k0, p0);
                startCameraPaths(k0, p0, p1);
                traceCamera();
                do shadeBounce(aovs);
                while (traceContinuing());
            }
        sampling_.endRound(aovs.rgb);
    }
    const std::vector<uint32_t>& done = sampling_.samplesDone();
    aovs.writeInto(film, x0, y0, tw_, th_, done);
    for (size_t p = 0; p < done.size(); ++p) stats.cameraRays += done[p];
    stats.rays += rayCount_;
}

/// The tile's pixels: the keys of their random numbers and their jitter rotations.
void TileRenderer::startTile(int x0, int y0, int x1, int y1) {
    const RenderSettings& settings = scene_.settings;
    x0_ = x0;
    y0_ = y0;
    tw_ = x1 - x0;
    th_ = y1 - y0;
    const size_t pixels = size_t(tw_) * th_;
    rayCount_ = 0;
    pixelKeys_.resize(pixels);
    rotations_.resize(2 * pixels);
    for (int j = 0; j < th_; ++j) {
        for (int i = 0; i < tw_; ++i) {
            uint32_t p = static_cast<uint32_t>(j * tw_ + i);
            uint64_t id = uint64_t(y0 + j) * settings.width + (x0 + i);
            const uint64_t key = pixelKey(settings.seed, id);
            pixelKeys_[p] = key;
            // Pixel jitter: the R2 sequence over the samples, rotated per pixel.
            rotations_[2 * p] = randomAt(key, dimension::kPixelSample, dimension::kJitterRotationX);
            rotations_[2 * p + 1] =
                randomAt(key, dimension::kPixelSample, dimension::kJitterRotationY);
        }
    }
}

/// How many samples `pixel` takes in the pass that starts k0 samples into this round.
uint32_t TileRenderer::samplesInPass(uint32_t pixel, uint32_t k0) const {
    const uint32_t left = sampling_.samplesTarget()[pixel] - sampling_.samplesDone()[pixel];
    return std::min(left - std::min(left, k0), kSamplesPerPass);
}

/// The end of the group of pixels that starts at pixelBegin: about kPathsPerGroup paths, at
/// least one pixel.
uint32_t TileRenderer::groupEnd(uint32_t k0, uint32_t pixelBegin) const {
    const uint32_t pixels = static_cast<uint32_t>(pixelKeys_.size());
    size_t count = 0;
    uint32_t p = pixelBegin;
    while (p < pixels && (p == pixelBegin || count + samplesInPass(p, k0) <= kPathsPerGroup))
        count += samplesInPass(p++, k0);
    return p;
}

/// The camera paths of pixels [pixelBegin, pixelEnd) in the pass that starts k0 samples into
/// this round: up to kSamplesPerPass per pixel, pixel by pixel. A pixel's samples keep their
/// order whatever the grouping, so its sums do too.
void TileRenderer::startCameraPaths(uint32_t k0, uint32_t pixelBegin, uint32_t pixelEnd) {
    const std::vector<uint32_t>& done = sampling_.samplesDone();
    size_t count = 0;
    for (uint32_t p = pixelBegin; p < pixelEnd; ++p) count += samplesInPass(p, k0);
    // Only the fields a new camera path needs are reset: the state is large, and resetting all
    // of it for every sample was a measurable share of a render.
    paths_.resize(count);
    size_t next = 0;
    for (uint32_t p = pixelBegin; p < pixelEnd; ++p) {
        const int i = static_cast<int>(p % static_cast<uint32_t>(tw_));
        const int j = static_cast<int>(p / static_cast<uint32_t>(tw_));
        const uint64_t key = pixelKeys_[p];
        const uint32_t s0 = done[p] + k0;
        const uint32_t s1 = s0 + samplesInPass(p, k0);
        for (uint32_t s = s0; s < s1; ++s) {
            PathState& path = paths_[next++];
            path.throughput = {1, 1, 1};
            path.radiance = {};
            path.diffuse = {};
            path.depth = 0;
            path.bsdfPdf = 0;
            path.alive = true;
            path.minRoughness = 0;
            path.glue = nullptr;
            path.pixel = p;
            path.sample = s;
            double jx = rotations_[2 * p] + s * 0.7548776662466927;
            double jy = rotations_[2 * p + 1] + s * 0.5698402909980532;
            jx -= std::floor(jx);
            jy -= std::floor(jy);
            path.filmX = x0_ + i + jx;
            path.filmY = y0_ + j + jy;
            path.ray = cameraSampler_.primary(path, key);
        }
    }
}

/// The camera rays, in packets of 16.
void TileRenderer::traceCamera() {
    for (size_t base = 0; base < paths_.size(); base += 16) {
        int count = static_cast<int>(std::min<size_t>(16, paths_.size() - base));
        PathState& first = paths_[base];
        rays_.intersect16({&first.ray, sizeof(PathState)}, count, {&first.hit, sizeof(PathState)});
    }
    rayCount_ += paths_.size();
}

/// The rays of the paths that go on; false if none does.
bool TileRenderer::traceContinuing() {
    bool any = false;
    for (PathState& path : paths_) {
        if (!path.alive) continue;
        any = true;
        path.hit = rays_.intersect(path.ray);
        ++rayCount_;
    }
    return any;
}

/// One bounce of every live path: what each hit is on, the wood there (in coherent batches),
/// then each vertex shaded, its light samples traced together.
void TileRenderer::shadeBounce(TileAovs& aovs) {
    locateBoards();
    woodHits_.evaluate(paths_, woodPaths_, pixelKeys_);
    shadows_.clear();
    finished_.assign(paths_.size(), 0);
    for (uint32_t i = 0; i < paths_.size(); ++i) {
        PathState& path = paths_[i];
        if (!path.alive) continue;
        shade(i, path, aovs);
    }
    traceShadows(aovs);
}

/// What the surface hits are on: the object's material, and in laminated products the board
/// (its tree, tint and lamella id) and the distance to the glue line. Collects woodPaths_.
void TileRenderer::locateBoards() {
    woodPaths_.clear();
    for (uint32_t i = 0; i < paths_.size(); ++i) {
        PathState& path = paths_[i];
        if (!path.alive || !path.hit.hit || path.hit.isLight) continue;
        const SceneObject& object = scene_.objects[path.hit.index];
        path.material = object.material;
        path.worldFromObject = &object.worldFromObject;
        path.lamella = -1;
        path.boardTint = object.boardTint;
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
        if (scene_.materials[path.material].type == MaterialType::Wood) woodPaths_.push_back(i);
    }
}

/// The light samples of this bounce, in 16-ray packets; then, in path order, each path gets its
/// unoccluded contributions (in light order) and finished paths go into the film: the same
/// sums in the same order as tracing each shadow ray where it was made.
void TileRenderer::traceShadows(TileAovs& aovs) {
    traceShadowRays(rays_, shadows_);
    rayCount_ += shadows_.size();
    size_t next = 0;
    for (uint32_t i = 0; i < paths_.size(); ++i) {
        PathState& path = paths_[i];
        for (; next < shadows_.size() && shadows_[next].path == i; ++next) {
            const ShadowRay& shadow = shadows_[next];
            if (!shadow.blocked) {
                path.radiance = path.radiance + shadow.contribution;
                path.diffuse = path.diffuse + shadow.diffuse;
            }
            if (shadow.camera) aovs.addDirect(path.pixel, shadow.contribution, shadow.blocked);
        }
        if (!finished_[i]) continue;
        aovs.addRadiance(path.pixel, path.radiance, path.diffuse);
        sampling_.addSample(path.pixel, path.sample, path.radiance);
    }
}

/// One path vertex: the light the ray found by itself, or a surface: its BSDF (the material
/// step), next-event estimation, and the bounce that continues the path.
void TileRenderer::shade(uint32_t index, PathState& path, TileAovs& aovs) {
    if (path.depth == 1) aovs.addFirstBounce(path.pixel, path.hit, path.cameraHitDistance);
    if (!path.hit.hit || path.hit.isLight) {
        addEmission(path, aovs);
        finish(index, path);
        return;
    }
    const Vec3 wo = -path.ray.direction;
    const bool camera = path.depth == 0;

    // The surface: normals facing the incoming ray.
    const Material& material = scene_.materials[path.material];
    const WoodSurfaceSample* wood = woodHits_.at(index);
    Vec3 ng = path.hit.geometricNormal;
    Vec3 ns = path.hit.shadingNormal;
    if (dot(ng, wo) < 0) ng = -ng;
    if (dot(ns, ng) < 0) ns = -ns;
    // The material step, once for the camera samples of a pixel that see one board face.
    const bool shareable = camera && material.type == MaterialType::Wood && wood != nullptr &&
                           !(path.glue && path.glueCover > 0);
    const WoodHits::Evaluation evaluation = woodHits_.evaluation(index);
    const SurfaceShading* kept = shareable ? shared_.find(evaluation, ng) : nullptr;
    // Not copied when kept: the state is some 300 bytes, and most camera samples share it.
    if (!kept) {
        ownShading_ = materialBsdf(material, {.hit = &path.hit,
                                              .wo = wo,
                                              .ns = ns,
                                              .wood = wood,
                                              .boardTint = path.boardTint,
                                              .glue = path.glue,
                                              .glueCover = path.glueCover,
                                              .minRoughness = path.minRoughness});
        if (shareable) shared_.keep(evaluation, ng, ownShading_, scene_.lights.size());
    }
    const SurfaceShading& surface = kept ? *kept : ownShading_;
    const Vec3 woLocal = surface.frame.toLocal(wo);

    if (camera) {
        path.cameraHitDistance = path.hit.distance;
        aovs.addSurfaceHit(path.pixel, surface.bsdf.base, surface.ns,
                           path.hit.distance * dot(path.ray.direction, camera_.forward()));
        if (wood) aovs.addWoodHit(path.pixel, wood->T, wood->knot);
        if (path.sample == 0) aovs.lamella[path.pixel] = path.lamella;
    }

    // Next-event estimation: its shadow rays are traced with the others of this bounce.
    const BounceRandom random(pixelKeys_[path.pixel], path.sample, path.depth);
    const LitVertex vertex{.position = path.hit.position,
                           .ng = ng,
                           .surface = &surface,
                           .woLocal = woLocal,
                           .throughput = path.throughput,
                           .diffuseShare = path.diffuseShare,
                           .camera = camera,
                           .continues = path.depth + 1 < scene_.settings.maxDepth};
    directLight_.sample(vertex, random, shareable ? shared_.lightValues() : std::span<BsdfValue>(),
                        index, shadows_);

    if (!bounce(path, surface, ng, woLocal, random)) finish(index, path);
}

/// Light the path's ray found by itself: the environment or a rectangle light's face. Past the
/// camera it is weighed against next-event estimation at the vertex the ray left (MIS).
void TileRenderer::addEmission(PathState& path, TileAovs& aovs) const {
    const bool camera = path.depth == 0;
    Rgb le;
    double lightPdf = 0;
    if (!path.hit.hit) {
        le = directLight_.environmentRadiance(path.ray.direction);
        if (!camera)
            lightPdf =
                directLight_.environmentPdf(path.ray.direction, path.lastPosition, path.lastNormal);
    } else {
        const Light& l = scene_.lights[path.hit.index];
        le = rectLightRadiance(l, path.ray.direction);
        if (!camera)
            lightPdf = directLight_.rectPdf(path.hit.index, path.ray.direction, path.hit.distance,
                                            path.lastPosition, path.lastNormal);
        if (camera)
            aovs.addEmitterHit(path.pixel,
                               path.hit.distance * dot(path.ray.direction, camera_.forward()),
                               path.hit.geometricNormal);
    }
    double w = camera ? 1 : powerHeuristic(path.bsdfPdf, lightPdf);
    const Rgb found = multiply(path.throughput, le) * w;
    path.radiance = path.radiance + found;
    // An emitter the camera sees is no surface's diffuse light.
    if (!camera) path.diffuse = path.diffuse + multiply(path.diffuseShare, found);
}

/// Continues the path in a direction sampled from the BSDF, with Russian roulette from the
/// third vertex on; false if the path ends here.
bool TileRenderer::bounce(PathState& path, const SurfaceShading& surface, const Vec3& ng,
                          const Vec3& woLocal, const BounceRandom& random) const {
    SurfaceBsdf::Sample bs;
    bool more = path.depth + 1 < scene_.settings.maxDepth && [&] {
        const auto [u, v] = random.pair(dimension::kBsdfDirection);
        return surface.bsdf.sample(woLocal, random.at(dimension::kBsdfLobe), u, v, bs);
    }();
    Vec3 wi = more ? surface.frame.toWorld(bs.wi) : Vec3{};
    if (more && dot(wi, ng) <= 0) more = false;
    if (more) {
        if (path.depth == 0) path.diffuseShare = share(bs.diffuseWeight, bs.weight);
        path.throughput = multiply(path.throughput, bs.weight);
        if (path.depth >= 2) {
            double q = std::min(0.95, maxComponent(path.throughput));
            if (random.at(dimension::kRoulette) >= q)
                more = false;
            else
                path.throughput = path.throughput * (1 / q);
        }
    }
    if (!more || isBlack(path.throughput)) return false;
    path.bsdfPdf = bs.pdf;
    path.lastPosition = path.hit.position;
    path.lastNormal = ng;
    if (bs.roughness >= 1) path.minRoughness = kRegularisedRoughness;
    path.ray = {offsetOrigin(path.hit.position, ng, wi), wi};
    ++path.depth;
    return true;
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
