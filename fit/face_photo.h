#pragma once
/// One photographed face as the fit reads it: its colours and lightness at the statistics'
/// scale (256 x 256, renderer/stats), where each pixel lies in the sample, and the rings'
/// local direction (the structure tensor of L*, as photo-stats measures ring agreement).

#include <array>
#include <vector>

#include "fit/sample_file.h"
#include "renderer/stats/image_statistics.h"
#include "renderer/stats/ndimage_filters.h"

namespace nenrin {

/// A pixel where the photo shows a clear ring direction.
struct RingDirection {
    Vec3 position;  ///< in the sample, m
    Vec3 normal;    ///< unit, in the face's plane: across the rings (its sign means nothing)
    double weight;  ///< the structure's coherence, 0 .. 1
};

struct FacePhoto {
    const SampleFace* face = nullptr;
    std::array<Plane, 3> linear;            ///< R, G, B, scene-linear
    Plane lightness;                        ///< L*
    std::vector<RingDirection> directions;  ///< every `step`-th pixel, a border left out
    /// The fine texture's gradients (L* less its 2 px blur) as 3-D vectors, on the pixels of
    /// `directions`, scaled so that their mean square is 1 on every face. Fibres and pores are
    /// long along the fibre direction, so on any face (end grain or side) these gradients
    /// lie across it.
    std::vector<Vec3> fineGradients;
    /// Its structure tensor and figures (rounded as reported), measured once: each bake of
    /// the face is compared with them (ring agreement, colour, texture energy).
    GrainStructure structure;
    ImageStatistics figures;
    /// The sample position of pixel (column x, row y) of the 256 x 256 planes: the pixel
    /// centres of the first and last rows and columns lie on the face's edges.
    Vec3 position(int x, int y) const;
};

/// Reads the face's photograph (InputError naming it: unreadable, not finite, too small) and
/// measures its ring directions on every `step`-th pixel.
FacePhoto readFacePhoto(const SampleFace& face, int step = 2);

}  // namespace nenrin
