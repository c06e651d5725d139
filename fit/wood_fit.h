#pragma once
/// `nenrin fit`: a skeleton and a grain file that reproduce a photographed sample (docs/fit.md).
/// The pith line from the faces' ring directions (pith_fit.h), the ring series and colours
/// from the faces' colours around it (ring_profile.h), then each face baked through the result
/// and measured against its photograph.

#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "fit/knot_branch.h"
#include "fit/pith_fit.h"
#include "fit/radial_rings.h"
#include "fit/ring_warp.h"
#include "fit/sample_file.h"
#include "renderer/bake/baked_grid.h"
#include "skeleton/skeleton.h"

namespace nenrin {

struct FitOptions {
    int threads = 0;  ///< 0 = all cores
    /// Grain files whose keys the fit keeps where it sets none (the anatomy of a species
    /// preset): of several, the one whose bakes' texture comes nearest the photos'. None:
    /// nenrin's defaults (no anatomy).
    std::vector<std::string> baseGrains;
    /// Faces to leave out of the fit (by name): they are still baked and measured, which is
    /// how a fit is judged on faces it never saw.
    std::vector<std::string> heldOut;
    /// Knots: found in the photos and made branches of the skeleton (knot_find.h,
    /// knot_branch.h).
    bool knots = true;
    bool quiet = false;  ///< no progress line on a terminal
};

/// One face's bake against its photograph.
struct FaceFigures {
    std::string name;
    bool heldOut = false;
    double ringMedianDeg = 0;  ///< photo-stats --rings: ring normals against grad T
    double ringWithin15 = 0;   ///< share within 15 degrees
    double dE = 0, fineRatio = 0, midRatio = 0;
    BakedGrid bake;              ///< 256 x 256: R, G, B, A, T, knot
    Plane lightness;             ///< the bake's L*
    std::array<Plane, 3> photo;  ///< the photograph at 256 x 256, scene-linear
};

/// A bake's pixel (FaceFigures::bake) is knot wood where its knot share is past the top of
/// the knot colour's smoothstep: the knot colour and ring fits compare photo and bake there,
/// given at least kMinKnotWoodPixels such pixels.
inline bool isKnotWood(const float* bakePixel) { return bakePixel[5] >= 0.75f; }
constexpr int kMinKnotWoodPixels = 50;

/// A knot seen in one face's photograph and where the fitted wood's bake puts it.
struct KnotFigures {
    bool heldOut = false;
    FaceKnot photo;
    std::optional<FaceKnot> baked;  ///< the bake's strongest ring centre on that face
    double offsetMm = -1;           ///< photo to bake, mm (-1: the bake shows none)
};

/// The ring contrast of the knot wood in the photographs and the bakes (fit/knot_rings.h):
/// RMS of L* band-passed to a knot's ring scale; over `pixels` pixels of knot wood.
struct KnotRingContrast {
    double photo = 0, baked = 0;
    int pixels = 0;
};

/// How strongly the anatomy shows, fitted against the base grain's (1 = as it was;
/// fit/texture_match.h): the cells' on side and on end grain, the rest's on end grain.
struct TextureStrengths {
    double sideCells = 1, endCells = 1, endRest = 1;
    int bakes = 0;  ///< bakes the fit took
};

/// The halo round the knots as fitted (fit/knot_halo.h).
struct HaloFit {
    bool kept = false;  ///< the fitted halo is in the grain
    double width = 0;   ///< m across the stem (0 when not kept)
    double axial = 0;   ///< its stretch along the stem (0 when not kept)
    int bakes = 0;      ///< bakes it took
};

struct WoodFit {
    PithLine pith;
    RingWarp warp;
    RadialRings profile;
    /// Ring phase: the blur the late-wood profile was sharpened by (fit/profile_sharpening.h).
    double profileBlur = 0;
    /// The anatomy's darkening by ring phase taken out of the late-wood profile
    /// (fit/anatomy_tone.h); empty without anatomy.
    std::vector<double> anatomyTone;
    std::vector<KnotBranch> branches;  ///< one per knot (or pair of faces' knots) seen
    Skeleton skeleton;
    nlohmann::json grain;
    std::string base;  ///< the base grain chosen ("" for none)
    std::vector<FaceFigures> faces;
    std::vector<KnotFigures> knots;  ///< every face whose photograph shows a knot
    KnotRingContrast knotRings;      ///< of the knot wood, photographs and bakes
    TextureStrengths texture;
    HaloFit halo;
    std::vector<std::string> warnings;
    double seconds = 0;
};

WoodFit fitSample(const Sample& sample, const FitOptions& options);

/// fit.json: the figures, the pith, the ring series and the warnings.
nlohmann::json fitReport(const Sample& sample, const WoodFit& fit);

}  // namespace nenrin
