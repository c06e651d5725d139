#pragma once
/// Knots in a photographed face: where a branch crosses the face, its rings are closed loops
/// around the branch's pith, so the ring normals of a whole disc point at one place — unlike
/// the trunk's rings, whose normals all point one way across a face (their pith lies far off).
/// Each pixel votes along its ring normal (a Hough transform for centres); the votes' peak is
/// refined by least squares of the normal lines passing near it, over shrinking discs, then
/// moved to the centre of the innermost loop (an oblique branch draws eccentric ovals: its
/// pith is the centre of the innermost rings).

#include <optional>
#include <string>

#include "fit/pith_fit.h"
#include "fit/sample_file.h"
#include "renderer/stats/ndimage_filters.h"

namespace nenrin {

struct FaceKnot {
    std::string face;
    double column = 0, row = 0;  ///< the centre of the knot's rings, pixels of the 256^2 plane
    Vec3 centre;                 ///< the same in the sample, m
    double radius = 0;           ///< m: the knot's dark wood around the centre
    double evidence = 0;         ///< the votes' peak over their mean (knots: 5 and more)
    double coverage = 0;         ///< eighths of a turn around the centre whose rings point at it
    double darkening = 0;        ///< L* of the face's median less the knot's centre's
    /// The dark knot wood's outline as an ellipse: the ratio of its short to its long axis
    /// (1 = round: the branch crosses the face squarely; an oblique branch's section is
    /// longer by 1/cos of its angle to the face's normal) and the long axis (unit, in the
    /// face's plane).
    double roundness = 1;
    Vec3 longAxis;
    /// m: between the knot's rings near its centre (their mean spacing along the radius over
    /// the inner 30 px); 0 when fewer than 3 rings show there.
    double ringSpacing = 0;
};

/// The place on a face (its lightness at the statistics' scale, 256 x 256) that the most ring
/// normals point at, with its figures; none when it lies off the face.
std::optional<FaceKnot> strongestRingCentre(const Plane& lightness, const SampleFace& face);

/// A knot's rings point at one centre from at least 5 eighths of a turn, with the votes' peak
/// 4.5 times their mean, and its centre is darker than the face (5 L*); or it is a dark patch
/// (15 L*) that the rings circle all round (7 eighths, peak 3 times the mean). With a pith line,
/// centres within 10 mm of it are the pith itself (an end-grain face through the pith), not knots.
bool looksLikeKnot(const FaceKnot& centre, const PithLine* pith);

/// The clearest knot on a face, or none.
std::optional<FaceKnot> findFaceKnot(const Plane& lightness, const SampleFace& face,
                                     const PithLine* pith);

}  // namespace nenrin
