#pragma once
/// The wood at one bounce's hits on wood materials. The growth field is only fast on coherent
/// batches, so the hits are grouped by material and board (the tree a lamella is cut from),
/// each batch evaluated in tree space, and the results brought back to world space.
///  - Camera hits get the full surface response (filtered rings, fibre, relief), shaded once
///    per pixel and board at the mean of its samples' points over the whole pixel's footprint;
///    pixels on a knot's edge, which the ring filter cannot smooth, once per quarter pixel.
///  - Later bounces, where the light is already blurred, get the albedo only, per hit.
///  - Hits near a glued boundary get their share of the box-filtered glue line (glueCover).

#include <cstdint>
#include <span>
#include <vector>

#include "renderer/path_state.h"
#include "renderer/scene.h"
#include "shader/wood_shader.h"

namespace nenrin {

class WoodHits {
public:
    /// `scene` must outlive this.
    WoodHits(const Scene& scene, const CameraSampler& camera) : scene_(scene), camera_(camera) {}

    /// Evaluates the wood at paths[i] for every i in `woodPaths` (increasing; paths whose hit
    /// is on a wood material, all at one depth) and sets their glueCover. `pixelKeys`: the key
    /// of the random numbers of each pixel of the tile (sample_dimensions.h).
    void evaluate(std::span<PathState> paths, std::span<const uint32_t> woodPaths,
                  std::span<const uint64_t> pixelKeys);

    /// The wood at path i's hit (world-space directions), or null if it is not on wood.
    const WoodSurfaceSample* at(uint32_t path) const {
        return slot_[path] >= 0 ? &results_[static_cast<size_t>(slot_[path])] : nullptr;
    }

    /// Which evaluation path i's wood came from: paths that share one (the camera samples of a
    /// pixel, or of a quadrant on a knot's edge) have the same, and since each evaluate()
    /// starts a new round, no result of an earlier bounce ever compares equal.
    struct Evaluation {
        uint64_t round = 0;
        int32_t slot = -1;
        bool operator==(const Evaluation&) const = default;
    };
    Evaluation evaluation(uint32_t path) const { return {round_, slot_[path]}; }

private:
    /// The hits on one material and board, in path order: entry k's scratch below (points_,
    /// footprints_, pixel_, ...) is at index k.
    struct Batch {
        std::span<PathState> paths;
        std::span<const uint32_t> entries;  ///< index into paths of each entry
        const WoodShader* shader;
        RigidTransform treeFromWorld;
        bool camera;
        PathState& path(size_t k) const { return paths[entries[k]]; }
    };
    void gather(const Batch& batch, std::span<const uint64_t> pixelKeys);
    SurfaceFootprint cameraFootprint(const PathState& path, uint64_t pixelKey,
                                     const RigidTransform& treeFromWorld) const;
    void shadeCameraWood(const Batch& batch);
    void refineKnotEdges(const Batch& batch);
    void evaluateIndirect(const Batch& batch);
    void coverGlue(const Batch& batch);
    void keepResults(const Batch& batch);
    int32_t keep(WoodSurfaceSample w, const RigidTransform& worldFromTree);

    const Scene& scene_;
    CameraSampler camera_;
    uint64_t round_ = 0;
    std::vector<WoodSurfaceSample> results_;  ///< this round's, world-space directions
    std::vector<int32_t> slot_;               ///< per path: its result, or -1
    // Scratch, reused by every batch.
    std::vector<uint32_t> sorted_;  ///< woodPaths by material, board, then path order
    WoodScratch scratch_;
    std::vector<Vec3> points_;  ///< per entry, tree space
    std::vector<SurfaceFootprint> footprints_;
    std::vector<uint32_t> pixel_;
    std::vector<WoodSurfaceSample> indirect_;
    std::vector<WoodSample> plain_;
    // Camera hits shaded once per pixel and board (shadeCameraWood): the groups of entries.
    std::vector<uint32_t> groupStart_;
    std::vector<Vec3> groupPoints_;
    std::vector<SurfaceFootprint> groupFootprints_;
    std::vector<WoodSurfaceSample> groupResults_;
    // Knot edges shaded per quarter pixel (refineKnotEdges).
    std::vector<int32_t> refineEntries_;  ///< per entry: its quadrant evaluation, or -1
    std::vector<int32_t> refineSlots_;
    std::vector<Vec3> refinePoints_;
    std::vector<SurfaceFootprint> refineFootprints_;
    std::vector<WoodSurfaceSample> refineResults_;
};

}  // namespace nenrin
