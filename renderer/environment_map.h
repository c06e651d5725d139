#pragma once
/// Lat-long environment maps (OpenImageIO) with importance sampling.
///
/// Directions are scene directions (right-handed, +Y up); radiance is scene-linear Rec.709 RGB.
///
/// Lat-long mapping. For a unit direction d the image coordinates are
///     u = 0.5 + atan2(d.x, -d.z) / (2 pi)      (0 = left edge, 1 = right edge)
///     v = acos(clamp(d.y, -1, 1)) / pi          (0 = top row = straight up, 1 = straight down)
/// so the image centre (u, v) = (0.5, 0.5) is -Z, u = 0.75 is +X (seen from inside, facing the
/// centre, the panorama is not mirrored), u = 0.25 is -X and the left/right edges are +Z. Texel
/// (i, j) of a W x H image covers u in [i/W, (i+1)/W), v in [j/H, (j+1)/H); its centre is at
/// ((i + 0.5)/W, (j + 0.5)/H).
///
/// Rotation. `rotation` (radians) turns the map about +Y, counter-clockwise seen from above:
/// what the unrotated map shows in direction d appears in direction Ry(rotation) d, i.e. the
/// lookup uses u + rotation / (2 pi). Rotating by pi/2 moves the image centre from -Z to -X.
///
/// Lookup and sampling. radiance() interpolates bilinearly between texel centres (wrapping in u,
/// clamped in v), so a texel's light reaches half a texel into its neighbours. Sampling uses a
/// piecewise-constant 2D distribution over the texels (marginal over rows, conditional per row):
/// a texel's weight is the exact integral over its solid angle of the luminance (Rec.709 Y) of
/// radiance(), i.e. luminance x sin(theta) of the texels after the bilinear spread (1/8, 3/4,
/// 1/8 of the texel before, at and after it, in u and likewise in v). So pdf() is positive
/// wherever radiance() is and radiance / pdf is an unbiased estimate of the sphere integral; a
/// lone lit texel draws 9/16 of the samples and its eight neighbours the rest. Within a texel
/// the density is constant per solid angle (uniform in phi and in cos theta): pdf() is the value
/// of the texel containing the direction (nearest texel), while radiance() varies within it.
/// sample() and pdf() both read the density off the stored cumulative tables (float per row),
/// so they agree to rounding and are the true density of sample().
/// A black map samples the sphere uniformly.
///
/// Immutable after construction: every const method is thread-safe and deterministic.

#include <string>
#include <vector>

#include "grain/rgb.h"
#include "util/vec3.h"

namespace nenrin {

class EnvironmentMap {
public:
    /// A constant environment of the given radiance (finite, non-negative) with uniform sphere
    /// sampling: pdf() is 1 / (4 pi) everywhere.
    static EnvironmentMap constant(const Rgb& radiance);

    /// Loads a lat-long image (any format OpenImageIO reads; EXR expected, scene-linear Rec.709).
    /// Any size of at least 2 x 1 texels is accepted (2:1 is the natural aspect). The first three
    /// channels are R, G, B; a single channel is grey and is replicated. `scale` (finite,
    /// >= 0) multiplies the radiance; `rotation` (radians) is described above. Throws
    /// InputError naming the file for a missing or unreadable file, two channels, a bad scale,
    /// and a non-finite or negative texel (naming the pixel and channel).
    static EnvironmentMap load(const std::string& path, double scale, double rotation);

    /// Radiance arriving from `direction` (unit length): bilinear lookup between texel centres.
    Rgb radiance(const Vec3& direction) const;

    /// A sampled direction, its radiance (as radiance() returns it) and its density per solid
    /// angle (as pdf() returns it).
    struct Sample {
        Vec3 direction;
        Rgb radiance;
        double pdf;
    };

    /// Importance-samples a direction from two uniform numbers in [0, 1): u1 picks the row
    /// (marginal), u2 the texel within it (conditional); each then places the direction within
    /// the texel uniformly in solid angle, so stratified inputs give stratified directions.
    Sample sample(double u1, double u2) const;

    /// Density per solid angle of sample() for `direction` (unit length): the piecewise-constant
    /// value of the texel containing it, consistent with sample().pdf.
    double pdf(const Vec3& direction) const;

    bool isConstant() const { return width_ == 0; }

    /// The mean radiance over the sphere, solid-angle weighted: exactly (up to rounding) the
    /// integral of radiance() over all directions divided by 4 pi.
    Rgb averageRadiance() const { return average_; }

private:
    EnvironmentMap() = default;

    struct Location {
        double u, v;  // image coordinates, rotation applied; u in [0, 1), v in [0, 1]
        int i, j;     // the texel containing (u, v)
    };
    Location locate(const Vec3& direction) const;
    Rgb texel(int i, int j) const;
    Rgb bilinear(double u, double v) const;
    double texelPdf(int i, int j) const;
    Vec3 directionAt(double u, double cosTheta) const;
    void buildDistribution();

    int width_ = 0, height_ = 0;  // 0 x 0 for a constant map
    double rotationU_ = 0;        // rotation / (2 pi), in [0, 1)
    Rgb constant_;
    Rgb average_;
    std::vector<float> texels_;            // RGB, row 0 at the top, scale applied
    std::vector<double> rowCdf_;           // height + 1 entries, 0 .. 1
    std::vector<float> columnCdf_;         // height rows of width + 1 entries, 0 .. 1 each
    std::vector<double> cosRowEdge_;       // cos(theta) at the top of row j (height + 1 entries)
    std::vector<double> texelSolidAngle_;  // per row
};

}  // namespace nenrin
