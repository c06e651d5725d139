#pragma once
/// A picture of a skeleton as a tree: every segment a round cone (Embree round linear curves
/// with per-node radii) on a ground disc under a sun and a sky, framed automatically. Living
/// wood is bark-brown, branches with a death time grey, so dieback shows at a glance. For
/// `nenrin tree preview`; the grain itself is not involved.

#include <string>
#include <vector>

#include "skeleton/skeleton.h"

namespace nenrin {

struct TreePreviewOptions {
    int width = 800, height = 1000;
    int spp = 16;          ///< samples per pixel (stratified jitter, seeded)
    double azimuth = 30;   ///< degrees: where the camera stands around the tree (0 = +X)
    double elevation = 8;  ///< degrees above the horizontal
    int threads = 0;       ///< 0 = all cores
    /// Radius used for nodes that carry none (hand-written skeletons): m per year of age, so
    /// older wood is thicker. Thin twigs are widened to at least half a pixel to stay visible.
    double radiusPerYear = 0.004;
};

struct TreePreview {
    std::vector<float> rgb;  ///< scene-linear, width x height x 3, row 0 at the top
    int width = 0, height = 0;
    size_t segments = 0;
    bool estimatedRadii = false;  ///< the skeleton had no radii: they came from node ages
};

TreePreview renderTreePreview(const Skeleton& skeleton, const TreePreviewOptions& options);

}  // namespace nenrin
