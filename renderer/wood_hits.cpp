#include "renderer/wood_hits.h"

#include <algorithm>
#include <cmath>

namespace nenrin {

namespace {

/// A pixel whose shared wood evaluation is on a knot's edge (knot share between this and
/// 1 - this) is shaded per quarter pixel.
constexpr double kKnotRefinement = 0.02;

/// Share of a footprint of diameter `footprint` centred `distance` from the middle of a line
/// of `width`: the box-filtered glue line, so it neither aliases nor vanishes far away.
double glueCoverage(double distance, double width, double footprint) {
    if (footprint <= 1e-3 * width) return distance <= 0.5 * width ? 1 : 0;
    double overlap = std::min(distance + 0.5 * width, 0.5 * footprint) -
                     std::max(distance - 0.5 * width, -0.5 * footprint);
    return std::clamp(overlap / footprint, 0.0, 1.0);
}

}  // namespace

void WoodHits::evaluate(std::span<PathState> paths, std::span<const uint32_t> woodPaths,
                        std::span<const uint64_t> pixelKeys) {
    ++round_;
    slot_.assign(paths.size(), -1);
    results_.clear();
    // Coherent batches: by material, then board, then path order (pixel-major).
    auto before = [&](uint32_t a, uint32_t b) {
        const PathState& pa = paths[a];
        const PathState& pb = paths[b];
        if (pa.material != pb.material) return pa.material < pb.material;
        return pa.treeFromObject < pb.treeFromObject;
    };
    sorted_.assign(woodPaths.begin(), woodPaths.end());
    // Often one board fills the tile: then the order is already right.
    if (!std::is_sorted(sorted_.begin(), sorted_.end(), before))
        std::stable_sort(sorted_.begin(), sorted_.end(), before);
    size_t begin = 0;
    while (begin < sorted_.size()) {
        const PathState& first = paths[sorted_[begin]];
        size_t end = begin + 1;
        while (end < sorted_.size()) {
            const PathState& p = paths[sorted_[end]];
            if (p.material != first.material || p.treeFromObject != first.treeFromObject) break;
            ++end;
        }
        const Batch batch{paths, std::span<const uint32_t>(sorted_).subspan(begin, end - begin),
                          scene_.materials[first.material].wood,
                          (*first.treeFromObject) * first.worldFromObject->inverse(),
                          first.depth == 0};
        gather(batch, pixelKeys);
        if (batch.camera) {
            shadeCameraWood(batch);
            refineKnotEdges(batch);
        } else {
            evaluateIndirect(batch);
        }
        coverGlue(batch);
        keepResults(batch);
        begin = end;
    }
}

/// The batch's tree-space points, and the camera footprints that shadeCameraWood and the glue
/// line need.
void WoodHits::gather(const Batch& batch, std::span<const uint64_t> pixelKeys) {
    const size_t n = batch.entries.size();
    points_.resize(n);
    footprints_.resize(batch.camera ? n : 0);
    pixel_.resize(n);
    for (size_t k = 0; k < n; ++k) {
        const PathState& p = batch.path(k);
        pixel_[k] = p.pixel;
        points_[k] = batch.treeFromWorld.point(p.hit.position);
        // Footprints for the first sample of each pixel (shadeCameraWood) and for samples
        // near glue lines.
        if (batch.camera && (k == 0 || pixel_[k] != pixel_[k - 1] || p.glue))
            footprints_[k] = cameraFootprint(p, pixelKeys[p.pixel], batch.treeFromWorld);
    }
}

/// A camera sample's footprint: where the neighbouring pixels' rays (scaled to the sample's
/// share of the pixel) meet the hit's plane.
SurfaceFootprint WoodHits::cameraFootprint(const PathState& p, uint64_t pixelKey,
                                           const RigidTransform& treeFromWorld) const {
    const Vec3& n0 = p.hit.geometricNormal;
    auto onPlane = [&](const Ray& r) {
        double den = dot(n0, r.direction);
        if (std::abs(den) < 1e-12) return p.hit.position;
        double t = dot(n0, p.hit.position - r.origin) / den;
        return r.origin + r.direction * t;
    };
    CameraRay c = camera_.withDifferentials(p, pixelKey);
    return {treeFromWorld.vector(onPlane(c.rayX) - p.hit.position),
            treeFromWorld.vector(onPlane(c.rayY) - p.hit.position), 0, treeFromWorld.vector(n0)};
}

/// The wood seen by camera samples is shaded once per pixel and board: where the pixel
/// centre's ray meets the board's plane (with a lens, or where that lies outside the pixel's
/// footprint, at the mean of the samples' tree-space points), filtered over the whole pixel's
/// footprint (the per-sample differentials are 1 / differentialScale shorter). The ring
/// profile is prefiltered over that footprint, so this is the pixel's box-filtered wood, as
/// the mean of the samples' own (smaller-footprint) evaluations would be, at 1/spp of the
/// cost. Light, visibility and geometry stay sampled per sample. Entries of one pixel are
/// adjacent (pixel-major). Fills groupResults_ (one per pixel) and groupStart_.
void WoodHits::shadeCameraWood(const Batch& batch) {
    const size_t n = batch.entries.size();
    groupStart_.clear();
    groupPoints_.clear();
    groupFootprints_.clear();
    const double widen = 1 / camera_.differentialScale();
    const bool pinhole = !camera_.camera().hasLens();
    for (size_t k = 0; k < n; ++k) {
        if (k == 0 || pixel_[k] != pixel_[k - 1]) {
            groupStart_.push_back(static_cast<uint32_t>(k));
            groupPoints_.push_back({0, 0, 0});
            groupFootprints_.push_back({footprints_[k].dpdx * widen, footprints_[k].dpdy * widen, 0,
                                        footprints_[k].normal});
        }
        groupPoints_.back() = groupPoints_.back() + points_[k];
    }
    groupStart_.push_back(static_cast<uint32_t>(n));
    const size_t groups = groupPoints_.size();
    for (size_t g = 0; g < groups; ++g)
        groupPoints_[g] = groupPoints_[g] * (1.0 / (groupStart_[g + 1] - groupStart_[g]));
    // With a pinhole camera the pixel is shaded where its centre's ray meets the board's
    // plane, not at its samples' mean: that mean wanders with the samples by a few hundredths
    // of a pixel, enough to move the pores and speckle under it by a few per cent, and the
    // denoiser multiplies that noise back into the image with the albedo (table-top-room at
    // 32 spp: 21 % of the wood's pixels differed from 128 spp's by over 2 %, now 4 %: edges,
    // glue lines and knots' rims). A lens spreads a pixel's samples over its own footprint.
    if (pinhole)
        for (size_t g = 0; g < groups; ++g) {
            const PathState& p = batch.path(groupStart_[g]);
            const Ray r = camera_.camera().primary(std::floor(p.filmX) + 0.5,
                                                   std::floor(p.filmY) + 0.5, 0, 0);
            const Vec3& n0 = p.hit.geometricNormal;
            const double den = dot(n0, r.direction);
            if (std::abs(den) < 1e-12) continue;
            const double t = dot(n0, p.hit.position - r.origin) / den;
            if (!(t > 0)) continue;
            // Beyond the pixel's footprint (a board seen edge-on, a curved face) the plane is
            // no stand-in for the surface: the mean stays.
            const Vec3 centre = batch.treeFromWorld.point(r.origin + r.direction * t);
            const SurfaceFootprint& f = groupFootprints_[g];
            if (length(centre - groupPoints_[g]) <= length(f.dpdx) + length(f.dpdy))
                groupPoints_[g] = centre;
        }
    groupResults_.resize(groups);
    batch.shader->evaluateSurface(groupPoints_, groupFootprints_, groupResults_, scratch_);
}

/// Knots are not prefiltered: a knot's rim would alias if a whole pixel took one evaluation,
/// so pixels on a knot's edge are shaded per quarter pixel: each sample takes the evaluation
/// of its quadrant (centroid, half-pixel footprint). Fills refineEntries_ and refineResults_.
void WoodHits::refineKnotEdges(const Batch& batch) {
    refineEntries_.assign(batch.entries.size(), -1);
    refinePoints_.clear();
    refineFootprints_.clear();
    const double half = 0.5 / camera_.differentialScale();
    for (size_t g = 0; g + 1 < groupStart_.size(); ++g) {
        const double knot = groupResults_[g].knot;
        const uint32_t g0 = groupStart_[g], g1 = groupStart_[g + 1];
        if (knot <= kKnotRefinement || knot >= 1 - kKnotRefinement || g1 - g0 < 2) continue;
        int32_t slotOfQuadrant[4] = {-1, -1, -1, -1};
        uint32_t count[4] = {0, 0, 0, 0};
        for (uint32_t k = g0; k < g1; ++k) {
            const PathState& p = batch.path(k);
            int q =
                (p.filmX - std::floor(p.filmX) >= 0.5) + 2 * (p.filmY - std::floor(p.filmY) >= 0.5);
            if (slotOfQuadrant[q] < 0) {
                slotOfQuadrant[q] = static_cast<int32_t>(refinePoints_.size());
                refinePoints_.push_back({0, 0, 0});
                refineFootprints_.push_back({footprints_[g0].dpdx * half,
                                             footprints_[g0].dpdy * half, 0,
                                             footprints_[g0].normal});
            }
            Vec3& sum = refinePoints_[static_cast<size_t>(slotOfQuadrant[q])];
            sum = sum + points_[k];
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
        batch.shader->evaluateSurface(refinePoints_, refineFootprints_, refineResults_, scratch_);
}

/// Later bounces: the albedo per hit, from one field evaluation each.
void WoodHits::evaluateIndirect(const Batch& batch) {
    const size_t n = batch.entries.size();
    indirect_.resize(n);
    plain_.resize(n);
    batch.shader->evaluate(points_, plain_, scratch_.growth, scratch_.samples);
    for (size_t k = 0; k < n; ++k) {
        WoodSurfaceSample& w = indirect_[k];
        w = WoodSurfaceSample{};
        w.albedo = plain_[k].albedo;
        w.coverage = plain_[k].coverage;
        w.T = plain_[k].T;
        w.knot = plain_[k].knot;
    }
}

/// The glue line's share of each footprint near one: a camera sample's own footprint, a point
/// at later bounces.
void WoodHits::coverGlue(const Batch& batch) {
    for (size_t k = 0; k < batch.entries.size(); ++k) {
        PathState& p = batch.path(k);
        if (p.glue) {
            double footprint = 0;
            if (batch.camera)
                footprint = std::sqrt(std::max(lengthSquared(footprints_[k].dpdx),
                                               lengthSquared(footprints_[k].dpdy)));
            p.glueCover = glueCoverage(p.glueDistance, p.glue->width, footprint);
        }
    }
}

/// Results in world space (directions back from tree space), one per camera pixel group or
/// quadrant, or per indirect hit; each path points at its result.
void WoodHits::keepResults(const Batch& batch) {
    const RigidTransform worldFromTree = batch.treeFromWorld.inverse();
    if (!batch.camera) {
        for (size_t k = 0; k < batch.entries.size(); ++k)
            slot_[batch.entries[k]] = keep(indirect_[k], worldFromTree);
        return;
    }
    // Quadrant results first, so each is kept once.
    refineSlots_.resize(refineResults_.size());
    for (size_t r = 0; r < refineResults_.size(); ++r)
        refineSlots_[r] = keep(refineResults_[r], worldFromTree);
    for (size_t g = 0; g + 1 < groupStart_.size(); ++g) {
        const uint32_t g0 = groupStart_[g], g1 = groupStart_[g + 1];
        const bool refined = refineEntries_[g0] >= 0;
        int32_t slot = refined ? -1 : keep(groupResults_[g], worldFromTree);
        for (uint32_t k = g0; k < g1; ++k)
            slot_[batch.entries[k]] =
                refined ? refineSlots_[static_cast<size_t>(refineEntries_[k])] : slot;
    }
}

int32_t WoodHits::keep(WoodSurfaceSample w, const RigidTransform& worldFromTree) {
    w.fibre = worldFromTree.vector(w.fibre);
    w.reliefGradient = worldFromTree.vector(w.reliefGradient);
    results_.push_back(w);
    return static_cast<int32_t>(results_.size() - 1);
}

}  // namespace nenrin
