#pragma once
/// The late-wood profile of a fit, sharpened. The fit reads a ring's early-to-late-wood profile
/// (E over the ring's phase, grain/colour_strip) from the photographs' colours averaged over
/// thin shells of the fitted ring surfaces; where those surfaces miss a photographed ring by a
/// fraction of a millimetre, the average blurs it: hinoki's thin dark late-wood line comes out
/// a wide soft band. The ring boundary (late wood to the next year's early wood, or into a
/// ring-porous wood's pore band) is abrupt in real wood, so the width of the profile's steepest
/// fall there measures the blur; the profile is then deconvolved by it (Richardson-Lucy with a
/// periodic Gaussian: E stays in [0, 1]). Behind a line a few samples wide the fall is
/// narrower than a step's, so the blur is taken low (0.7-0.8 of it for hinoki's kind of line):
/// the profile keeps some blur rather than gaining invented sharpness.

#include <vector>

namespace nenrin {

struct SharpenedProfile {
    std::vector<double> profile;  ///< E at the same phases, sharpened
    double blur = 0;              ///< the Gaussian's standard deviation, in ring phase (0 .. 1)
};

/// `profile`: E at evenly spaced phases of one ring, the first at its start and the last at its
/// end (grain/colour_strip's 33), taken as periodic. A profile without a clear fall (under 0.1
/// in E) or with one no wider than its sampling is returned as it is.
SharpenedProfile sharpenLateWoodProfile(const std::vector<double>& profile);

/// The profile blurred by a periodic Gaussian of `blur` (ring phase): what the fit's shell
/// average makes of a sharp one (the tests blur known profiles with it).
std::vector<double> blurLateWoodProfile(const std::vector<double>& profile, double blur);

}  // namespace nenrin
