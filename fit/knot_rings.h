#pragma once
/// The contrast of the knots' rings: knot wood is compression wood, its late wood dark, so a
/// photographed knot shows thin dark ring lines where the stem's rings, carried into the knot,
/// are soft bands. The grain's `colour.knots.ring_darkening` is set so that the bakes' knot
/// wood has the photographs' ring contrast.

#include <functional>
#include <nlohmann/json.hpp>
#include <span>
#include <vector>

#include "fit/face_photo.h"
#include "fit/wood_fit.h"

namespace nenrin {

/// Ring contrast over the bakes' knot wood (knot share 0.75 and more) of the fitted faces: the
/// RMS of L* band-passed to the scale of a knot's rings (Gaussian 1 px less Gaussian 4 px at
/// 256 x 256), in the photographs and in the bakes alike. `photos` and `faces` in one order.
KnotRingContrast knotRingContrast(std::span<const FacePhoto> photos,
                                  std::span<const FaceFigures> faces);

/// Sets `colour.knots.ring_darkening` of `grain` (0 .. 0.9) so that the bakes' knot ring
/// contrast is the photographs': one probe bake 0.3 up (or down, where the base grain's rings
/// are too contrasted), then the value on the line through the two (contrast grows about
/// linearly with it), and `rebake` once more. `faces` are the bakes of `grain` as it is;
/// `rebake` bakes them again from `grain`. Without enough knot wood (kMinKnotWoodPixels), or
/// where the bake's rings are as contrasted as the photo's already (within 5 %), changes
/// nothing.
void matchKnotRings(nlohmann::json& grain, std::vector<FaceFigures>& faces,
                    std::span<const FacePhoto> photos,
                    const std::function<std::vector<FaceFigures>()>& rebake);

}  // namespace nenrin
