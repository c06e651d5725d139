#include "grain/wood_colour.h"

#include <algorithm>

#include "grain/growth_terms.h"

namespace nenrin {

Rgb woodColour(const GrowthSample& s, const Vec3& treePoint, const ColourParams& c) {
    return woodColour(s, treePoint, c, lateWoodFraction(s.T, c.lateWoodExponent), 1.0);
}

Rgb woodColour(const GrowthSample& s, const Vec3& treePoint, const ColourParams& c, double e,
               double microWeight) {
    Rgb colour = mix(c.earlyWood, c.lateWood, e);  // eq. 6: C = E Cd + (1 - E) Cl
    if (c.heartwood) {
        double h = heartwoodWeight(s.T, c.heartwoodStart, c.heartwoodEnd);
        colour = colour + mix(c.sapwoodOffset, c.heartwoodOffset, h);
    }
    double brightness = 1 + microWeight * c.microAmplitude *
                                microStructure(treePoint, c.microCellSize, c.microSeed);
    brightness *= 1 - knotEmphasis(s.knot, s.deadKnot, c);
    colour = colour * brightness;
    return {std::max(colour.r, 0.0), std::max(colour.g, 0.0), std::max(colour.b, 0.0)};
}

}  // namespace nenrin
