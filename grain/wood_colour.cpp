#include "grain/wood_colour.h"

#include <algorithm>

#include "grain/growth_terms.h"
#include "grain/knot_look.h"

namespace nenrin {

Rgb woodColour(const GrowthSample& s, const Vec3& treePoint, const ColourParams& c) {
    return woodColour(s, treePoint, c,
                      lateWoodFraction(colourTime(s, treePoint, c), lateWoodShape(c)), 1.0);
}

Rgb woodColour(const GrowthSample& s, const Vec3& treePoint, const ColourParams& c, double e,
               double microWeight, double footprint) {
    Rgb colour = mix(c.earlyWood, c.lateWood, e);  // eq. 6: C = E Cd + (1 - E) Cl
    if (c.heartwood) {
        double h = heartwoodWeight(s.T, c.heartwoodStart, c.heartwoodEnd);
        colour = colour + mix(c.sapwoodOffset, c.heartwoodOffset, h);
    }
    double brightness = 1 + microWeight * c.microAmplitude *
                                microStructure(treePoint, c.microCellSize, c.microSeed);
    const KnotLook knot = knotLook(s, c, footprint);
    brightness *= 1 - knot.darkening;
    // Knot wood's late wood, darker than the stem's (compression wood).
    if (knot.tint > 0) brightness *= 1 - c.knotRingDarkening * knot.tint * e;
    // Knot wood's own hue, where the knot's branch wins the blend.
    if (knot.tint > 0)
        colour = multiply(
            colour,
            mix(Rgb{1, 1, 1}, mix(c.knotTint, c.deadKnotTint, knot.deadFraction), knot.tint));
    // The discoloured stem wood round it.
    if (c.knotHaloTint != Rgb{1, 1, 1}) {
        const double halo = (1 - knot.tint) * knotHalo(s, treePoint, c);
        if (halo > 0) colour = multiply(colour, mix(Rgb{1, 1, 1}, c.knotHaloTint, halo));
    }
    colour = colour * brightness;
    return {std::max(colour.r, 0.0), std::max(colour.g, 0.0), std::max(colour.b, 0.0)};
}

Rgb endGrainAlbedo(const Rgb& albedo, double cosFibre, const ColourParams& c) {
    double c2 = cosFibre * cosFibre;
    if (c.endGrainTint.r >= 0) return multiply(albedo, mix(Rgb{1, 1, 1}, c.endGrainTint, c2 * c2));
    double d = c.endGrainDarkening * c2 * c2;
    return {albedo.r * (1 - d * (1 - c.endGrainRedness)), albedo.g * (1 - d), albedo.b * (1 - d)};
}

double endGrainWeight(double cosFibre) {
    const double c2 = cosFibre * cosFibre;
    return c2 * c2;
}

}  // namespace nenrin
