// Wood anatomy: vessels only where the species has them (a band in the early wood for
// ring-porous woods, throughout for diffuse-porous ones, none in conifers), rays across the
// rings on end grain, and every feature fading to its mean under a wide footprint.

#include "shader/wood_anatomy.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "skeleton/skeleton_index.h"
#include "tests/shader/structure_tensor.h"
#include "tests/test_trees.h"

namespace nenrin {
namespace {

class Anatomy : public ::testing::Test {
protected:
    Anatomy() : skeleton_(test::straightTrunk(10, 0.5)), index_(skeleton_) {
        grain_.radialSpeed = 0.004;
        field_ = std::make_unique<GrowthField>(index_, grain_);
        params_.enabled = true;
    }
    /// Anatomy at p with grad T from the field (point samples unless a footprint is given).
    AnatomySample at(const Vec3& p, double diameter = 0) const {
        GrowthSample s = field_->evaluate(p);
        const double h = 1e-6;
        Vec3 g{(field_->evaluate(p + Vec3{h, 0, 0}).T - s.T) / h,
               (field_->evaluate(p + Vec3{0, h, 0}).T - s.T) / h,
               (field_->evaluate(p + Vec3{0, 0, h}).T - s.T) / h};
        return woodAnatomy(params_, s, p, g, {}, {}, diameter);
    }
    /// Mean pore coverage over points of one ring phase band, on many radii and heights.
    double poresInPhase(double lo, double hi) const {
        double sum = 0;
        int n = 0;
        for (int ring = 10; ring < 20; ++ring)
            for (int k = 0; k < 40; ++k) {
                double phase = lo + (hi - lo) * (k + 0.5) / 40;
                double r = (ring + phase) * grain_.radialSpeed;  // T = r / Sb at z = 0
                for (int a = 0; a < 50; ++a) {
                    double az = 2 * std::numbers::pi * a / 50;
                    sum += at({r * std::cos(az), r * std::sin(az), 0.0001 * a}).pore;
                    ++n;
                }
            }
        return sum / n;
    }
    Skeleton skeleton_;
    SkeletonIndex index_;
    GrainParams grain_;
    std::unique_ptr<GrowthField> field_;
    AnatomyParams params_;
};

TEST_F(Anatomy, RingPorousWoodHasItsLargeVesselsInTheEarlyWoodBand) {
    params_.pores = PoreKind::RingPorous;
    params_.poreBand = 0.25;
    params_.poreDiameter = 0.0003;
    params_.poreSpacing = 0.0006;
    double early = poresInPhase(0.0, 0.24), late = poresInPhase(0.3, 0.97);
    EXPECT_GT(early, 0.05);
    // Past the band a few small late-wood vessels: 0.3 of the cells, 0.4 of the size.
    EXPECT_GT(late, 0);
    EXPECT_LT(late, 0.1 * early);
}

TEST_F(Anatomy, DiffusePorousWoodHasVesselsThroughoutAndConifersNone) {
    params_.pores = PoreKind::DiffusePorous;
    params_.poreDiameter = 0.00008;
    params_.poreSpacing = 0.0003;
    double early = poresInPhase(0.0, 0.3), late = poresInPhase(0.4, 0.9);
    // The expected cover: 0.45 x pi/4 x (0.08 / 0.3)^2 x 0.75 run / 1.6 = 0.012.
    EXPECT_GT(early, 0.006);
    EXPECT_GT(late, 0.006);
    EXPECT_LT(std::abs(early - late) / early, 0.5);
    params_.pores = PoreKind::None;
    EXPECT_EQ(poresInPhase(0.0, 1.0), 0);
}

/// Share of an n x n map's gradient that runs along the radius about an axis `offset` m left
/// of the map's centre (rays that radiate from it give ~0, an isotropic pattern ~0.64);
/// `rays` gets the mean coverage.
double radialGradientShare(const std::vector<double>& map, int n, double step, double offset,
                           double* rays) {
    double radialPart = 0, total = 0;
    *rays = 0;
    for (int j = 1; j + 1 < n; ++j)
        for (int i = 1; i + 1 < n; ++i) {
            double gy = map[size_t(j) * n + i + 1] - map[size_t(j) * n + i - 1];
            double gz = map[size_t(j + 1) * n + i] - map[size_t(j - 1) * n + i];
            double y = offset + (i - n / 2) * step, z = (j - n / 2) * step, r = std::hypot(y, z);
            if (r < 10 * step) continue;  // the pith
            radialPart += std::abs((gy * y + gz * z) / r);
            total += std::hypot(gy, gz);
            *rays += map[size_t(j) * n + i] / (double(n) * n);
        }
    return total > 0 ? radialPart / total : 1;
}

// On a cross cut (end grain) rays are lines across the rings: the ray map changes along the
// rings (tangentially) and not across them (radially). Measured as the orientation of its
// gradient on a grid 80 mm from the pith.
TEST_F(Anatomy, RaysRunAcrossTheRingsOnEndGrain) {
    params_.raySpacing = 0.001;
    params_.rayWidth = 0.0002;
    params_.rayHeight = 0.01;
    const double step = 0.00005, z = 0.5;
    const int n = 200;
    std::vector<double> map(size_t(n) * n);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            map[size_t(j) * n + i] = at({0.08 + (i - n / 2) * step, (j - n / 2) * step, z}).ray;
    double rays = 0;
    const double share = radialGradientShare(map, n, step, 0.08, &rays);
    EXPECT_GT(rays, 0.01);  // rays are there
    EXPECT_LT(share, 0.2);  // ~0.64 for an isotropic pattern
}

// Inside a knot the anatomy is drawn about the branch (as the shader does with the field's
// knot frame): on a cut across a horizontal branch its rays radiate from the knot's pith.
// Drawn about the trunk's axis instead, they would cross the knot as parallel lines.
TEST(KnotAnatomy, RaysRadiateFromTheKnotsPithOnItsCrossSection) {
    ChainProperties props;
    props.gamma = 0.3;
    Skeleton sk = test::trunkWithBranch(2, {1, 0, 0}, 1.0, props);
    SkeletonIndex index(sk);
    GrainParams grain;
    grain.radialSpeed = 0.004;
    grain.junction.p = 4;
    GrowthField field(index, grain);
    AnatomyParams params;
    params.enabled = true;
    params.raySpacing = 0.001;  // as RaysRunAcrossTheRingsOnEndGrain, sampled as finely
    params.rayWidth = 0.0002;
    params.rayHeight = 0.01;
    const double x = 0.06, step = 0.00005;
    const int n = 200;  // a 1 cm square around the branch's axis, inside its knot
    std::vector<double> knotFrame(size_t(n) * n), trunkFrame(size_t(n) * n);
    std::vector<Vec3> points;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            points.push_back({x, (i - n / 2) * step, 2 + (j - n / 2) * step});
    std::vector<GrowthSample> samples(points.size());
    GrowthScratch scratch;
    field.evaluateBatch(points, samples, scratch);
    int inKnot = 0;
    for (size_t k = 0; k < points.size(); ++k) {
        const GrowthSample& s = samples[k];
        inKnot += s.knot > 0.6;
        // grad T in the knot: outward from the branch's axis at the branch's speed.
        const double r = length(s.knotOffset);
        Vec3 g = r > 0 ? s.knotOffset * (1 / (r * grain.radialSpeed * props.gamma)) : Vec3{};
        knotFrame[k] =
            woodAnatomy(params, {s.knotOffset, s.knotAxisDirection}, s.T, points[k], g, {}, {}).ray;
        trunkFrame[k] = woodAnatomy(params, s, points[k], g, {}, {}).ray;
    }
    ASSERT_GT(inKnot, n * n * 9 / 10);
    double rays = 0, trunkRays = 0;
    const double share = radialGradientShare(knotFrame, n, step, 0, &rays);
    const double trunkShare = radialGradientShare(trunkFrame, n, step, 0, &trunkRays);
    RecordProperty("radial_share", std::to_string(share));
    std::printf("knot rays: radial share %.3f (about the trunk's axis: %.3f)\n", share, trunkShare);
    EXPECT_GT(rays, 0.005);  // rays are there
    // New rays start as the branch's circumference grows (an octave of radius apart): their
    // starts are the radial part. The trunk's rays in the same place give more than 0.5.
    EXPECT_LT(share, 0.35);
    EXPECT_GT(trunkShare, 0.5);
}

// Wide footprints: each feature gives way to its mean, so a distant board keeps its tone.
TEST_F(Anatomy, WideFootprintsGiveTheMeanOfTheSharpFeatures) {
    params_.pores = PoreKind::DiffusePorous;
    params_.poreDiameter = 0.0001;
    params_.poreSpacing = 0.0004;
    params_.raySpacing = 0.001;
    params_.rayWidth = 0.00015;
    params_.fibreAmplitude = 0;
    double sharp = 0, wide = 0;
    int n = 0;
    // 0.4 rad of arc (50 vessel cells, 20 rays along it) by 4 mm radially: enough cells for
    // their mean to settle within the tolerance.
    for (int a = 0; a < 200; ++a)
        for (int k = 0; k < 200; ++k) {
            double r = 0.05 + 0.00002 * k, az = 0.002 * a;
            Vec3 p{r * std::cos(az), r * std::sin(az), 0.3 + 0.00003 * a};
            sharp += at(p).filter().r;
            ++n;
        }
    for (int k = 0; k < 50; ++k) {
        double r = 0.05 + 0.00008 * k;
        wide += at({r, 0, 0.3 + 0.0001 * k}, 0.02).filter().r;
    }
    EXPECT_NEAR(wide / 50, sharp / n, 0.003);
    EXPECT_LT(sharp / n, 0.999);  // the features darken on average
}

// Vessels smaller than a pixel: a pixel's filtered coverage is the share of it they cover,
// as a box average of point samples gives, in the mean and in the dark tail (the pixels a
// vessel falls in), instead of fading to the mean and leaving a photograph's dots out.
TEST_F(Anatomy, VesselsSmallerThanAPixelDarkenItByTheirShare) {
    params_.pores = PoreKind::DiffusePorous;
    params_.poreDiameter = 0.00025;
    params_.poreSpacing = 0.0004;
    params_.rayWidth = 0;
    const double pixel = 0.0002;
    std::vector<double> filtered, boxed;
    for (int i = 0; i < 60; ++i)
        for (int j = 0; j < 60; ++j) {
            const Vec3 corner{0.05 + pixel * i, 0.001 + pixel * j, 0.3};
            filtered.push_back(at(corner + Vec3{0.5 * pixel, 0.5 * pixel, 0}, pixel).pore);
            double sum = 0;
            for (int a = 0; a < 8; ++a)
                for (int b = 0; b < 8; ++b)
                    sum += at(corner + Vec3{(a + 0.5) / 8 * pixel, (b + 0.5) / 8 * pixel, 0}).pore;
            boxed.push_back(sum / 64);
        }
    auto mean = [](const std::vector<double>& v) {
        double s = 0;
        for (double x : v) s += x;
        return s / double(v.size());
    };
    auto quantile = [](std::vector<double> v, double q) {
        std::sort(v.begin(), v.end());
        return v[size_t(q * double(v.size() - 1))];
    };
    std::printf(
        "vessel coverage, filtered against 64 point samples a pixel: mean %.4f / %.4f, "
        "quantiles 0.5 %.3f / %.3f, 0.8 %.3f / %.3f, 0.95 %.3f / %.3f\n",
        mean(filtered), mean(boxed), quantile(filtered, 0.5), quantile(boxed, 0.5),
        quantile(filtered, 0.8), quantile(boxed, 0.8), quantile(filtered, 0.95),
        quantile(boxed, 0.95));
    EXPECT_GT(mean(boxed), 0.03);
    EXPECT_NEAR(mean(filtered), mean(boxed), 0.1 * mean(boxed));
    for (double q : {0.5, 0.8, 0.95})
        EXPECT_NEAR(quantile(filtered, q), quantile(boxed, q), 0.06)
            << "quantile " << q << " mean " << mean(filtered) << " against " << mean(boxed);
}

/// How directional a feature is on an end-grain patch 3.2 mm across, at 7 cm from the pith and
/// azimuth `azimuth`: the eigenvalue ratio of the structure tensor of `value` over the patch
/// (about 1 for round features, large for streaks).
template <class Value>
double endGrainAnisotropy(double azimuth, Value value) {
    constexpr int n = 80;
    constexpr double step = 0.00004;
    const Vec3 radial{std::cos(azimuth), std::sin(azimuth), 0};
    const Vec3 tangential{-std::sin(azimuth), std::cos(azimuth), 0};
    std::vector<double> v(n * n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            v[i * n + j] = value(radial * (0.07 + step * (i - n / 2)) + tangential * (step * j) +
                                 Vec3{0, 0, 0.3});
    return test::structureTensorRatio(v, n);
}

// The anatomy's lattice is polar (arcs at a fixed radius per annulus or vessel row), not
// rho * theta, which shears it by the azimuth: round cells and vessels turned into slanted
// streaks on end grain away from the frame's zero azimuth (ratios of 3 to 9 at 0.3 and 2.8 rad).
TEST_F(Anatomy, EndGrainCellsAndVesselsAreRoundAtEveryAzimuth) {
    params_.fibreAmplitude = 0;
    params_.rayWidth = 0;
    params_.speckleAmplitude = 0.3;
    params_.speckleSize = params_.speckleRadial = 0.0002;
    for (double azimuth : {0.3, 1.5, 2.8})
        EXPECT_LT(endGrainAnisotropy(azimuth, [&](const Vec3& p) { return at(p).filter().r; }), 1.6)
            << "speckle at azimuth " << azimuth;
    params_.speckleAmplitude = 0;
    params_.pores = PoreKind::DiffusePorous;
    params_.poreDiameter = 0.0003;
    params_.poreSpacing = 0.0006;
    for (double azimuth : {0.3, 1.5, 2.8})
        EXPECT_LT(endGrainAnisotropy(azimuth, [&](const Vec3& p) { return at(p).pore; }), 1.6)
            << "vessels at azimuth " << azimuth;
}

// Brown vessels: with a pore tint each channel darkens by its share of the darkening, so the
// open pores of oak or chestnut are brown, not grey; the tint (1, 1, 1) is the grey default.
TEST_F(Anatomy, PoreTintDarkensEachChannelByItsShare) {
    params_.pores = PoreKind::DiffusePorous;
    params_.poreDiameter = 0.0004;
    params_.poreSpacing = 0.0006;
    params_.poreDarkening = 0.8;
    params_.fibreAmplitude = 0;
    params_.rayWidth = 0;
    params_.poreTint = {0.4, 0.7, 1};
    int inPores = 0;
    for (int a = 0; a < 400; ++a) {
        const double r = 0.05, az = 0.00002 * a;
        const AnatomySample s = at({r * std::cos(az), r * std::sin(az), 0.3});
        if (s.pore < 0.5) continue;
        ++inPores;
        // 1 - filter is the darkening each channel gets: in the tint's proportions.
        EXPECT_NEAR((1 - s.filter().r) / (1 - s.filter().b), 0.4, 1e-9);
        EXPECT_NEAR((1 - s.filter().g) / (1 - s.filter().b), 0.7, 1e-9);
        EXPECT_NEAR(1 - s.filter().b, 0.8 * s.pore, 1e-9);
    }
    EXPECT_GT(inPores, 10);
}

// The strongest texture a grain file can ask for on end grain: cell amplitudes of 0.5 each and
// pores darkening 1, times 1 + 4 (colour.end_grain texture and contrast at their limit).
// The filter would go below zero on some 3 % of the face (a negative albedo, found by
// baking such a grain): it stops at zero.
TEST_F(Anatomy, TheStrongestTextureAGrainAllowsNeverMakesANegativeFilter) {
    params_.fibreAmplitude = params_.speckleAmplitude = 0.5 * 5;
    params_.pores = PoreKind::DiffusePorous;
    params_.poreDarkening = 1.0 * 5;
    int zero = 0;
    for (int a = 0; a < 4000; ++a) {
        const double r = 0.01 + 0.00002 * a, az = 0.37 * a;
        const AnatomySample s = at({r * std::cos(az), r * std::sin(az), 0.3});
        for (double c : {s.filter().r, s.filter().g, s.filter().b}) {
            EXPECT_GE(c, 0.0);
            zero += c == 0;
        }
    }
    EXPECT_GT(zero, 0) << "the case reaches the bound";
}

}  // namespace
}  // namespace nenrin
