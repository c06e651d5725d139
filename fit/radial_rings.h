#pragma once
/// The sample's rings along the radius: once the pith line and the warp are known every pixel
/// of every face has a ring radius (warpedRingRadius), and the faces' colours averaged over
/// thin shells of equal ring radius (0.1 mm) make a strip from the innermost pixel to the
/// outermost, like a strip photographed pith to bark. grain/colour_strip finds its rings (the
/// late-wood lines) and colours.

#include <span>
#include <string>
#include <vector>

#include "fit/face_photo.h"
#include "fit/pith_fit.h"
#include "fit/ring_warp.h"
#include "grain/colour_strip.h"

namespace nenrin {

struct RadialRings {
    double innerRadius = 0, outerRadius = 0;  ///< m: the sample's pixels lie between
    double binWidth = 0;                      ///< m: one strip column
    std::string face;        ///< the face whose band the series was read on ("" for all faces)
    double contrast = 0;     ///< L*: how clearly the rings stand out along the strip
    bool evenRings = false;  ///< no strip showed 3 whole rings: even rings of their period
    ColourStrip strip;
    std::vector<double> boundaries;  ///< m from the pith: where each ring's early wood begins
};

/// Where no strip shows 3 whole rings but some show their period, even rings of that period
/// (evenRings). Throws InputError naming `sampleFile` when no strip shows rings at all.
RadialRings measureRadialRings(std::span<const FacePhoto> faces, const PithLine& pith,
                               const RingWarp& warp, const std::string& sampleFile,
                               double binWidth = 1e-4);
// binWidth: the shells' thickness when the rings show no clear period; otherwise a twentieth
// of it.

/// A ring series for the skeleton (Skeleton::ringWidths, m per year) that puts ring
/// boundaries exactly at `boundaries`: the years inside the first boundary share its radius
/// evenly at about the mean width, the years past the last continue at the mean width out to
/// `outerRadius` and a few more.
std::vector<double> ringSeries(const std::vector<double>& boundaries, double outerRadius);

}  // namespace nenrin
