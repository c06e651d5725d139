#include "fit/face_photo.h"

#include <fmt/format.h>

#include <cmath>

#include "renderer/stats/image_statistics.h"
#include "renderer/stats/stats_image.h"
#include "util/input_error.h"

namespace nenrin {

namespace {

/// The structure tensor is smoothed over 8 px: nearer the edge it sees the reflection.
constexpr int kBorder = 8;

}  // namespace

Vec3 FacePhoto::position(int x, int y) const {
    const double last = kStatsSize - 1;
    return face->at(x / last, y / last);
}

FacePhoto readFacePhoto(const SampleFace& face, int step) {
    FacePhoto f;
    f.face = &face;
    const StatsRgb image = readStatsRgb(face.image);
    // The image is resampled to a square: its proportions must be the face's.
    const double imageAspect = double(image.sourceWidth) / image.sourceHeight;
    const double faceAspect = length(face.right) / length(face.up);
    if (std::abs(std::log(imageAspect / faceAspect)) > std::log(1.05))
        throw InputError(face.image, "",
                         fmt::format("{} x {} pixels, but the face is {:.1f} x {:.1f} mm: expected "
                                     "the photograph of the face, cropped to its edges",
                                     image.sourceWidth, image.sourceHeight,
                                     length(face.right) * 1e3, length(face.up) * 1e3));
    f.linear = image.linear;
    const std::array<Plane, 3> lab = labPlanes(f.linear);
    f.lightness = lab[0];
    f.structure = grainStructure(f.lightness);
    f.figures = roundedAsReported(imageStatistics(lab));
    const GrainStructure& s = f.structure;
    // Image x runs along `right`, image y down, against `up`.
    const Vec3 right = normalize(face.right), down = normalize(face.up) * -1.0;
    const Plane blurred = gaussianFilter(f.lightness, 2);
    Plane fine = f.lightness;
    for (size_t i = 0; i < fine.values.size(); ++i) fine.values[i] -= blurred.values[i];
    const Plane gx = sobel(fine, 1), gy = sobel(fine, 0);
    for (int y = kBorder; y < kStatsSize - kBorder; y += step)
        for (int x = kBorder; x < kStatsSize - kBorder; x += step) {
            const double angle = 0.5 * s.angle2.at(x, y);
            Vec3 n = right * std::cos(angle) + down * std::sin(angle);
            f.directions.push_back({f.position(x, y), normalize(n), s.coherence.at(x, y)});
            f.fineGradients.push_back(right * gx.at(x, y) + down * gy.at(x, y));
        }
    double square = 0;
    for (const Vec3& g : f.fineGradients) square += dot(g, g);
    if (square > 0) {
        const double scale = std::sqrt(double(f.fineGradients.size()) / square);
        for (Vec3& g : f.fineGradients) g = g * scale;
    }
    return f;
}

}  // namespace nenrin
