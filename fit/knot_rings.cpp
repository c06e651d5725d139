#include "fit/knot_rings.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "renderer/stats/ndimage_filters.h"

namespace nenrin {

namespace {

/// Ring scale at 256 x 256: a knot's rings are 1–1.5 mm apart, 5–8 px on a 50 mm face; the
/// 1 px blur takes out sanding scratches and pores, the 4 px one the knot's colour gradient.
constexpr double kFine = 1, kCoarse = 4;
constexpr double kProbe = 0.3, kMaxRingDarkening = 0.9;
/// Left alone when the bake is within this of the photo.
constexpr double kTolerance = 0.05;

Plane bandPass(const Plane& p) {
    Plane fine = gaussianFilter(p, kFine);
    const Plane coarse = gaussianFilter(p, kCoarse);
    for (size_t i = 0; i < fine.values.size(); ++i) fine.values[i] -= coarse.values[i];
    return fine;
}

}  // namespace

KnotRingContrast knotRingContrast(std::span<const FacePhoto> photos,
                                  std::span<const FaceFigures> faces) {
    if (photos.size() != faces.size())
        throw std::logic_error("knotRingContrast: photographs and bakes differ in number");
    double photo2 = 0, baked2 = 0;
    KnotRingContrast out;
    for (size_t i = 0; i < faces.size(); ++i) {
        const FaceFigures& f = faces[i];
        if (f.heldOut) continue;
        const Plane& photoL = photos[i].lightness;
        if (photoL.width != f.bake.width || photoL.height != f.bake.height ||
            f.lightness.width != f.bake.width || f.lightness.height != f.bake.height)
            throw std::logic_error("knotRingContrast: photograph and bake differ in size");
        bool any = false;
        for (int y = 0; y < f.bake.height && !any; ++y)
            for (int x = 0; x < f.bake.width && !any; ++x) any = isKnotWood(f.bake.at(x, y));
        if (!any) continue;
        const Plane p = bandPass(photoL), b = bandPass(f.lightness);
        // A border of the coarse blur's reach left out: the filters reflect at the edges.
        const int border = int(4 * kCoarse + 0.5);
        for (int y = border; y < f.bake.height - border; ++y)
            for (int x = border; x < f.bake.width - border; ++x) {
                if (!isKnotWood(f.bake.at(x, y))) continue;
                photo2 += p.at(x, y) * p.at(x, y);
                baked2 += b.at(x, y) * b.at(x, y);
                ++out.pixels;
            }
    }
    if (out.pixels > 0) {
        out.photo = std::sqrt(photo2 / out.pixels);
        out.baked = std::sqrt(baked2 / out.pixels);
    }
    return out;
}

void matchKnotRings(nlohmann::json& grain, std::vector<FaceFigures>& faces,
                    std::span<const FacePhoto> photos,
                    const std::function<std::vector<FaceFigures>()>& rebake) {
    const KnotRingContrast start = knotRingContrast(photos, faces);
    const double gap = start.photo - start.baked;
    if (start.pixels < kMinKnotWoodPixels || std::abs(gap) <= kTolerance * start.photo) return;
    nlohmann::json& knots = grain["colour"]["knots"];
    if (!knots.is_object()) knots = nlohmann::json::object();
    const double before = knots.value("ring_darkening", 0.0);
    // Towards the photographs' contrast: the base grain's value (a preset's) may be too much.
    const double probe =
        gap > 0 ? std::min(kMaxRingDarkening, before + kProbe) : std::max(0.0, before - kProbe);
    if (probe == before) return;  // at the end of the range already
    knots["ring_darkening"] = probe;
    faces = rebake();
    const KnotRingContrast probed = knotRingContrast(photos, faces);
    const double slope = (probed.baked - start.baked) / (probe - before);
    const double wanted = slope > 0 ? before + gap / slope : before;
    const double value = std::round(std::clamp(wanted, 0.0, kMaxRingDarkening) * 1e4) / 1e4;
    if (value == probe) return;
    knots["ring_darkening"] = value;
    faces = rebake();
}

}  // namespace nenrin
