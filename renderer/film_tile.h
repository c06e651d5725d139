#pragma once
/// A tile's share of the film while its samples are rendered: per-pixel sums of each channel,
/// which become the film's means once the tile is done. Each tile has its own, so threads never
/// share a sum, and a pixel adds its samples in sample order: the image is the same bytes for
/// any thread count.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "grain/rgb.h"
#include "renderer/film.h"
#include "renderer/ray_scene.h"
#include "util/vec3.h"

namespace nenrin {

/// The occlusion AOV's reach, a share of the camera ray's length (table-top-room denoised at 32
/// spp: FLIP 0.0116 with 0.05, 0.0114 with 0.15, 0.0115 with 0.4; 0.0117 without the guide).
constexpr double kOcclusionReach = 0.15;

struct TileAovs {
    /// Per pixel of the tile (row-major): radiance over all samples; the rest over the samples
    /// whose camera ray hit something (hits) or hit wood (woodHits).
    std::vector<Rgb> rgb, albedo;
    std::vector<Rgb> diffuse;  ///< the part of rgb the first hit's albedo carries
    std::vector<Vec3> normal;
    std::vector<double> hits, depth, woodHits, growthTime, knot;
    std::vector<double> luminanceSquares;  ///< sum over the samples of luminance squared
    /// Luminance of the camera hits' light samples: those nothing blocked, and all of them.
    std::vector<double> directUnblocked, directAll;
    /// Over the camera samples that bounced: the occlusion of each (addFirstBounce), and their
    /// count.
    std::vector<double> occlusion, bounces;
    std::vector<int32_t> lamella;  ///< the board the pixel's first sample hit, -1 if none

    explicit TileAovs(size_t n)
        : rgb(n),
          albedo(n),
          diffuse(n),
          normal(n),
          hits(n),
          depth(n),
          woodHits(n),
          growthTime(n),
          knot(n),
          luminanceSquares(n),
          directUnblocked(n),
          directAll(n),
          occlusion(n),
          bounces(n),
          lamella(n, -1) {}

    /// A finished sample's radiance, and the part of it its first hit's albedo carries.
    void addRadiance(uint32_t pixel, const Rgb& radiance, const Rgb& diffuseRadiance) {
        rgb[pixel] = rgb[pixel] + radiance;
        diffuse[pixel] = diffuse[pixel] + diffuseRadiance;
        const double y = luminance(radiance);
        luminanceSquares[pixel] += y * y;
    }

    /// A camera ray that found an emitter's face: a hit, without albedo.
    void addEmitterHit(uint32_t pixel, double viewDepth, const Vec3& geometricNormal) {
        hits[pixel] += 1;
        depth[pixel] += viewDepth;
        normal[pixel] += geometricNormal;
    }
    /// A camera ray that found a surface.
    void addSurfaceHit(uint32_t pixel, const Rgb& surfaceAlbedo, const Vec3& shadingNormal,
                       double viewDepth) {
        hits[pixel] += 1;
        albedo[pixel] = albedo[pixel] + surfaceAlbedo;
        normal[pixel] += shadingNormal;
        depth[pixel] += viewDepth;
    }
    /// A light sample at a camera ray's hit, blocked or not.
    void addDirect(uint32_t pixel, const Rgb& contribution, bool blocked) {
        const double y = luminance(contribution);
        directAll[pixel] += y;
        if (!blocked) directUnblocked[pixel] += y;
    }
    /// What a camera sample's first bounce found, `hit`, the camera ray having gone
    /// `cameraDistance`: as occlusion, 1 - t / R for a hit at t within R = kOcclusionReach x
    /// cameraDistance, else 0 (the reach grows with the distance, as a pixel's footprint does).
    void addFirstBounce(uint32_t pixel, const SurfaceHit& hit, double cameraDistance) {
        const double reach = kOcclusionReach * cameraDistance;
        if (hit.hit && hit.distance < reach) occlusion[pixel] += 1 - hit.distance / reach;
        bounces[pixel] += 1;
    }
    /// A camera ray that found wood.
    void addWoodHit(uint32_t pixel, double T, double knotShare) {
        woodHits[pixel] += 1;
        growthTime[pixel] += T;
        knot[pixel] += knotShare;
    }

    /// The means into the film's pixels of the tile at (x0, y0), tw wide and th high, each
    /// pixel having taken samples[p] samples.
    void writeInto(Film& film, int x0, int y0, int tw, int th,
                   const std::vector<uint32_t>& samples) const;
};

}  // namespace nenrin
