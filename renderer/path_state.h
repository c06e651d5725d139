#pragma once
/// One sample's path in flight through the path tracer, and the camera sample it started from.
/// The samples of a tile travel together, one bounce at a time (renderer/path_tracer.h), so
/// each step of a bounce (wood evaluation, shading, shadow rays) works on all of them at once.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "grain/rgb.h"
#include "renderer/camera.h"
#include "renderer/geometry/rigid_transform.h"
#include "renderer/products/laminated_product.h"
#include "renderer/ray_scene.h"
#include "renderer/sample_dimensions.h"

namespace nenrin {

struct PathState {
    Ray ray;
    /// Film position of the camera sample (pixels): its ray differentials are made again
    /// from it where a footprint is needed, instead of being carried by every path.
    double filmX = 0, filmY = 0;
    Rgb throughput{1, 1, 1};
    Rgb radiance;
    /// The part of `radiance` that the first hit's albedo carries (the film's diffuse AOV),
    /// and per channel the share of the throughput that left the first hit by the BSDF's
    /// diffuse part: whatever the path finds later counts towards `diffuse` by that share.
    Rgb diffuse, diffuseShare;
    double cameraHitDistance = 0;  ///< how far the camera ray went (the occlusion AOV's scale)
    uint32_t pixel = 0;            ///< index within the tile
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

/// The camera rays of path samples: the lens point each sample draws, and the footprint
/// differentials, shortened to a sample's share of the pixel.
class CameraSampler {
public:
    /// `camera` must outlive this.
    CameraSampler(const Camera& camera, const RenderSettings& settings)
        : camera_(camera),
          differentialScale_(
              std::max(0.125, 1 / std::sqrt(double(static_cast<uint32_t>(settings.spp))))) {}

    const Camera& camera() const { return camera_; }
    /// How much shorter a sample's differentials are than a pixel's: 1 / sqrt(spp), at most 8x.
    double differentialScale() const { return differentialScale_; }

    /// The sample's point on the lens (a pinhole needs none); `pixelKey`: the key of the
    /// pixel's random numbers.
    std::pair<double, double> lensSample(const PathState& path, uint64_t pixelKey) const {
        if (!camera_.hasLens()) return {0, 0};
        return pairAt(pixelKey, path.sample, dimension::kLens);
    }
    /// The camera ray of a path's sample, without differentials.
    Ray primary(const PathState& path, uint64_t pixelKey) const {
        auto [lu, lv] = lensSample(path, pixelKey);
        return camera_.primary(path.filmX, path.filmY, lu, lv);
    }
    /// The camera ray of a path's sample, with its differentials.
    CameraRay withDifferentials(const PathState& path, uint64_t pixelKey) const {
        auto [lu, lv] = lensSample(path, pixelKey);
        return camera_.generate(path.filmX, path.filmY, lu, lv, differentialScale_);
    }

private:
    const Camera& camera_;
    double differentialScale_;
};

}  // namespace nenrin
