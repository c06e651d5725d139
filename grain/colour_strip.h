#pragma once
/// A ring colour profile measured from a photographed strip (pith to bark, one colour per
/// column; data/colour-bars shows the kind): the rings are found as the late-wood lines
/// (lightness minima), and from them the early and late wood colours (the brightest third and
/// the darkest tenth of each ring), the shape of the early-to-late-wood transition (E over the
/// ring phase), the heart-to-sapwood shift and the ring-width statistics. `nenrin grain strip`
/// turns a photo into grain colour keys with it, so a user can match their own timber.

#include <string>
#include <vector>

#include "grain/cielab.h"
#include "grain/rgb.h"
#include "skeleton/ring_series.h"

namespace nenrin {

struct ColourStrip {
    int rings = 0;
    std::vector<int> boundaries;     ///< columns where each ring starts (early wood begins)
    std::vector<double> ringWidths;  ///< px
    RingStatistics widthStatistics;
    Lab early, late;                      ///< mean over the rings
    Rgb earlyWood, lateWood;              ///< the same, scene-linear
    std::vector<double> lateWoodProfile;  ///< E at 33 evenly spaced ring phases
    Rgb heartwoodOffset, sapwoodOffset;   ///< inner 40 % and outer 30 % of the rings vs all
    double heartwoodEnd = 0;              ///< rings from the pith where the inner zone ends
};

/// Throws InputError (naming `name`) when the strip is too short or shows fewer than 3 rings.
ColourStrip analyseColourStrip(const std::vector<Rgb>& columns, const std::string& name);

/// The same figures for rings found otherwise: `boundaries` (at least 2, increasing, within
/// the strip) are the columns where each ring's early wood begins.
ColourStrip colourStripFromBoundaries(const std::vector<Rgb>& columns, std::vector<int> boundaries);

}  // namespace nenrin
