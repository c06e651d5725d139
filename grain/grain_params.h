#pragma once
/// Parameters of the growth-time field and the wood colour (Momoi 1994, models.md section 1),
/// with their defaults and units. Loaded from a "grain" JSON file, documented key by key in
/// docs/grain-format.md. Every default here is the value a grain file gets when it omits a key.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "grain/anatomy_params.h"
#include "grain/point_warp.h"
#include "grain/rgb.h"
#include "grain/ring_model.h"
#include "grain/ring_wander.h"
#include "util/vec3.h"

namespace nenrin {

/// Trunk-branch junction blend (eq. 5, our reconstruction) and its cut-off.
struct JunctionParams {
    double p = 2;      ///< smooth-min exponent: 2 is the paper's form, large values approach min()
    double reach = 4;  ///< a branch path stops counting (smoothly) once T_c / sin(alpha)
                       ///< exceeds reach x the trunk time: bounds the work per point
};

/// Eq. 7: the sun side grows faster.
struct DirectionParams {
    Vec3 sunRay{0, 1, 0};  ///< direction the sunlight travels (from the sun); unit length
    double strength = 0;   ///< eps of eq. 7, in [0, 0.95]
};

/// Eq. 8: Tb = (Db / S)^delta.
struct AgeParams {
    double delta = 1;
};

/// Eq. 9: S' = (1 + nu omega^Ta) S.
struct TaperParams {
    double nu = 0;
    double omega = 0.9;
};

/// Section 4.5: sway of the sample point and a direction-dependent factor on Db.
struct SwayParams {
    double amplitude = 0;     ///< m: displacement of the sample point
    double wavelength = 0.6;  ///< m: of the displacement sines
    double radialJitter = 0;  ///< relative: Db is multiplied by 1 + radialJitter * h, |h| <= 1
    uint64_t seed = 1;
};

/// Section 3 and 4.6: colours and micro-structure.
struct ColourParams {
    Rgb earlyWood{0.74, 0.50, 0.28};   ///< Cl: scene-linear
    Rgb lateWood{0.42, 0.20, 0.07};    ///< Cd: scene-linear
    double lateWoodExponent = 6;       ///< n of eq. 6: larger = narrower late-wood band
    double lateWoodShare = 0;          ///< > 0: an abrupt late-wood band this share of the ring
    double lateWoodTransition = 0.05;  ///< share of the ring over which the abrupt step rises
    double earlyWoodRise = 0;  ///< with the step: E at its start, rising through the early wood
    double lateWoodRamp = 0;   ///< with the step: E rises from 1 - ramp across the band
    /// A measured early-to-late-wood profile (E at evenly spaced ring phases, from
    /// `nenrin grain strip`); overrides the exponent and the share when not empty.
    std::vector<double> lateWoodProfile;
    bool heartwood = true;
    double heartwoodStart = 12;  ///< Th1, years: heartwood below
    double heartwoodEnd = 16;    ///< Th2, years: sapwood above
    Rgb heartwoodOffset{-0.06, -0.06, -0.03};
    Rgb sapwoodOffset{0.03, 0.03, 0.03};
    double microCellSize = 0.0008;  ///< m: one cell of the 16 x 16 micro-structure table
    double microAmplitude = 0.04;   ///< relative brightness change
    uint64_t microSeed = 7;
    double knotDarkening = 0.25;      ///< relative darkening inside living knots
    double deadKnotDarkening = 0.45;  ///< relative darkening inside dead knots
    double knotCore = 0.25;           ///< extra darkening at a knot's pith, fading to 0 at its edge
    /// Knot wood is compression wood: its late wood is darker than the stem's. Extra relative
    /// darkening of the late wood inside knots (times the late-wood share), drawing a knot's
    /// rings as the thin dark lines photographs show instead of the stem's soft bands.
    double knotRingDarkening = 0;
    double deadKnotRim = 0.5;  ///< relative darkening of the bark ring of dead knots
    /// m: the bark ring's width (the branch's bark when it died, encased by the trunk).
    double deadKnotRimWidth = 0.0015;
    double deadKnotChecks = 0.5;         ///< probability that a dead knot has a drying check
    double deadKnotCheckWidth = 0.0004;  ///< m: the check's widest opening
    /// Knot wood is compression wood, often resinous: its own hue, a filter on the wood colour
    /// inside living and dead knots (white = the stem's hue, only darkened).
    Rgb knotTint{1, 1, 1};
    Rgb deadKnotTint{1, 1, 1};
    /// The stem wood round a knot is often discoloured: resin-soaked and compression wood
    /// (conifers' "red wood"), orange to red-brown, reaching farther along the stem than across
    /// it because it follows the fibres. A filter on the wood colour there (white = none),
    /// full at the knot's edge and fading to none `knotHaloWidth` m out across the stem,
    /// `knotHaloWidth x knotHaloAxial` m out along it (grain/knot_look.h).
    Rgb knotHaloTint{1, 1, 1};
    double knotHaloWidth = 0.005;
    double knotHaloAxial = 3;
    /// A knot's rings are not the perfect circles a straight branch axis draws: the years by
    /// which a value noise of `knotRingWobbleScale` m moves them, inside knots (0 = circles).
    double knotRingWobble = 0;
    double knotRingWobbleScale = 0.003;
    /// End grain measures darker and redder than side grain (Hirata et al. 2020, 60 species):
    /// open cell ends trap light. At a surface cut across the fibre the albedo's green and
    /// blue are multiplied by 1 - endGrainDarkening, its red by 1 - endGrainDarkening x
    /// (1 - endGrainRedness); faces in between by the weight |cos(normal, fibre)|^4.
    double endGrainDarkening = 0.3;
    double endGrainRedness = 0.3;
    /// A measured end-grain colour instead: the factor (r, g, b) an end-grain face's albedo has
    /// against a side-grain face's, e.g. from photographs of both; r < 0: use the two above.
    Rgb endGrainTint{-1, -1, -1};
    /// Open cell ends show the cells' own texture (the anatomy's fibres and speckle) more
    /// strongly: its contrast is multiplied by 1 + endGrainTexture at a face cut across the
    /// fibre (same weight as the colour).
    double endGrainTexture = 0;
    /// The rest of the anatomy (streaks, ring tones, vessels) there: its contrast is
    /// multiplied by 1 + endGrainContrast (< 0 where a dark end grain swallows it).
    double endGrainContrast = 0;
};

struct GrainParams {
    double radialSpeed = 0.004;  ///< Sb, m/year: the trunk's ring width
    /// Years: the tree was felled then, so points with T > fellingTime are outside the log
    /// (bakes write A = 0 and black there). 0 = never felled: wood everywhere.
    double fellingTime = 0;
    JunctionParams junction;
    DirectionParams direction;
    AgeParams age;
    TaperParams taper;
    SwayParams sway;
    /// Ring-boundary waviness at the centimetre scale ("wander"; off by default).
    WanderParams wander;
    /// A measured displacement of the sample points ("warp": nenrin fit's; off by default).
    WarpParams warp;
    ColourParams colour;
    /// Yearly ring widths for skeletons that record none ("rings"; off = constant Sb).
    RingModelParams rings;
    /// Fibres, pores, rays, resin canals at close range ("anatomy"; off by default).
    AnatomyParams anatomy;
};

GrainParams loadGrainFile(const std::string& path);
GrainParams parseGrain(const nlohmann::json& json, const std::string& file);
/// The parameters as JSON (same keys as the file): stored as metadata in outputs.
nlohmann::json grainToJson(const GrainParams& params);

}  // namespace nenrin
