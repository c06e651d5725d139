#pragma once
/// Where a bake samples the tree: planar cuts through the log (slices) and boxes (volumes).
/// All positions are tree space: metres, +Z up the trunk.

#include <optional>
#include <string>

#include "renderer/bake/baked_grid.h"
#include "skeleton/skeleton.h"

namespace nenrin {

enum class SlicePlane {
    Cross,       ///< horizontal cut at height `at`: an end-grain "cookie"
    Radial,      ///< vertical cut, plane y = pith.y + at: quarter-sawn when at is near 0
    Tangential,  ///< vertical cut, plane x = pith.x + at: flat-sawn board face
};

SlicePlane parseSlicePlane(const std::string& name);  ///< throws InputError
const char* slicePlaneName(SlicePlane plane);

/// A cut through any plane (tree space, metres), the convention of the photographed cubes of
/// ../shared/data/mokume: `origin` is the image's bottom-left sample, `right` and `up` run from
/// it to the bottom-right and top-left samples, so the outermost samples lie on the edges.
/// (An image one sample wide or high has it in the middle.)
struct PlaneCut {
    Vec3 origin, right, up;
};

struct SliceSpec {
    /// When set, the slice is this plane and `plane`, `at`, `width`, `height` and `bottom` are
    /// not used.
    std::optional<PlaneCut> cut;
    SlicePlane plane = SlicePlane::Cross;
    double at = 1;  ///< m: height (cross) or offset from the pith (radial, tangential)
    double width = 0.4, height = 0.4;  ///< m: image extent (boards: width across, height along z)
    double bottom = 0;                 ///< m: boards only, height of the image's lower edge
    int resX = 512, resY = 512;
};

/// Sets up the sample grid of a slice (row 0 at the top of the image) and its normal: pixel
/// centres of the named planes (cross sections centred on the pith at that height, boards on
/// the pith at mid-height), or the samples of a PlaneCut.
BakedGrid sliceGrid(const Skeleton& skeleton, const SliceSpec& spec);

struct VolumeSpec {
    Vec3 lower{-0.2, -0.2, 0}, upper{0.2, 0.2, 1};
    int resolution = 64;  ///< samples along the longest box edge; others in proportion (>= 2)
};

/// Sets up the sample grid of a volume: samples at the box's lattice points, both faces
/// included (sample i of S at lower + i (upper - lower) / (S - 1)), as POV-Ray's df3 wants.
BakedGrid volumeGrid(const VolumeSpec& spec);

}  // namespace nenrin
