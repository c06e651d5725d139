#pragma once
/// How an image of wood looks, in numbers, and how well a growth field explains a photograph's
/// rings: the figures of the team's photo-stats script (docs/stats.md), with its definitions,
/// computed on 256 x 256 planes (stats_image.h). Every Gaussian and derivative is scipy's
/// (ndimage_filters.h).

#include <array>
#include <string>
#include <vector>

#include "renderer/stats/ndimage_filters.h"

namespace nenrin {

/// The figures of one image.
struct ImageStatistics {
    std::array<double, 3> lab{};  ///< mean L*, a*, b* (D65)
    double stdL = 0;              ///< standard deviation of L* (population)
    double fine = 0;              ///< std of L* - G4(L*): fibres, pores, specks (< ~1 mm)
    double mid = 0;               ///< std of G4(L*) - G16(L*): rings, streaks, figure (1-6 mm)
    double dirSpread = 0;         ///< circular spread of the grain direction, degrees
    double fineAniso = 0;         ///< how directional the fine layer is: 1 for white noise
};

/// An image against a photograph of the wood it should look like.
struct StatisticsAgainst {
    double dE = 0;              ///< dE*ab between the mean colours
    double fineRatio = 0;       ///< fine / the photo's
    double midRatio = 0;        ///< mid / the photo's
    double dirSpreadDiff = 0;   ///< dir_spread - the photo's, degrees
    double fineAnisoRatio = 0;  ///< fine_aniso / the photo's
};

/// A growth field's rings against a photograph's.
struct RingAgreement {
    double medianDeg = 0;  ///< coherence-weighted median angle between the ring normals
    double within15 = 0;   ///< coherence-weighted share of pixels within 15 degrees
};

/// The structure tensor of L* (Gaussian 1.5 px, Sobel, tensor smoothed over 8 px): twice the
/// angle of the dominant gradient (the ring normal) and its coherence (0 isotropic .. 1).
struct GrainStructure {
    Plane angle2, coherence;
};
GrainStructure grainStructure(const Plane& lightness);

/// Which figures imageStatistics computes: all, or only the mean colour, std_L, fine and mid
/// (dir_spread and fine_aniso left 0: they take four fifths of the filtering, and a caller
/// comparing colour and texture energy alone, as the fit does bake after bake, needs neither).
enum class Figures { kAll, kColourAndEnergy };

/// The figures of an image from its L*, a*, b* planes.
ImageStatistics imageStatistics(const std::array<Plane, 3>& lab, Figures figures = Figures::kAll);

/// The figures rounded as the script reports them (lab 2 decimals, std_L, fine and mid 3,
/// dir_spread and fine_aniso 2; fine_aniso capped at 10^4).
ImageStatistics roundedAsReported(const ImageStatistics& s);

/// `image` against `photo`, from their reported (rounded) figures as the script takes them;
/// ratios 3 decimals, differences 2. Throws InputError naming `photoPath` if the photo has no
/// fine or mid texture to take a ratio of.
StatisticsAgainst statisticsAgainst(const ImageStatistics& image, const ImageStatistics& photo,
                                    const std::string& photoPath);

/// The photo's ring normals (grainStructure of its L*) against the in-plane gradient of the
/// growth time T (Gaussian 2 px, Sobel), a 16 px border left out, weighted by coherence;
/// rounded as reported (median 2 decimals, share 3). Throws InputError naming `photoPath` if
/// the photo has no structure to weigh by (a flat image).
RingAgreement ringAgreement(const Plane& photoLightness, const Plane& growthTime,
                            const std::string& photoPath);
/// The same from the photo's grainStructure, for a photo measured against many fields.
RingAgreement ringAgreement(const GrainStructure& photo, const Plane& growthTime,
                            const std::string& photoPath);

/// The script's weighted median: values sorted, the first whose cumulative weight reaches half
/// the total (numpy searchsorted on the cumulative sum).
double weightedMedian(const std::vector<double>& values, const std::vector<double>& weights);

}  // namespace nenrin
