// The wood surface response: the ring prefilter against brute-force averaging over the
// footprint, grad T against the analytic trunk, and the fibre direction.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "grain/cielab.h"
#include "grain/growth_terms.h"
#include "shader/ring_profile.h"
#include "shader/wood_shader.h"
#include "skeleton/skeleton_index.h"
#include "tests/shader/structure_tensor.h"
#include "tests/test_trees.h"

namespace nenrin {
namespace {

TEST(RingProfile, FilteredMatchesTheMeanOfPointSamples) {
    for (double n : {1.0, 5.0, 12.0}) {
        RingProfile rings(n);
        for (double width : {0.01, 0.3, 1.0, 3.7, 10.0}) {
            for (double T : {3.1, 7.55, 12.999}) {
                const int samples = 20000;
                double sum = 0;
                for (int i = 0; i < samples; ++i)
                    sum += rings.lateWood(T + width * ((i + 0.5) / samples - 0.5));
                EXPECT_NEAR(rings.filtered(T, width), sum / samples, 2e-4)
                    << "n " << n << " width " << width << " T " << T;
            }
        }
    }
}

TEST(RingProfile, NonFiniteGrowthTimesStayInTheTable) {
    // An infinite T (a tiny elongation speed once made every birth time infinite) has no ring
    // phase; the table was indexed with int(NaN) and the shader crashed.
    RingProfile rings(4);
    for (double T :
         {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::quiet_NaN()}) {
        const double e = rings.lateWood(T);
        EXPECT_TRUE(std::isnan(e) || (e >= 0 && e <= 1)) << T;
        (void)rings.filtered(T, 0.5);
        (void)rings.filteredSlope(T, 0.5);
    }
    EXPECT_EQ(rings.lateWood(1e300), rings.lateWood(0));
}

TEST(RingProfile, TableFollowsEquationSix) {
    for (double n : {1.0, 5.0, 12.0}) {
        RingProfile rings(n);
        double worst = 0;
        for (int i = 0; i < 100000; ++i) {
            double T = 3 + i / 100000.0;
            worst = std::max(worst, std::abs(rings.lateWood(T) - lateWoodFraction(T, n)));
        }
        EXPECT_LT(worst, 5e-5) << "n " << n;
    }
}

TEST(RingProfile, WideFootprintsTendToTheRingMean) {
    RingProfile rings(5);
    EXPECT_NEAR(rings.filtered(10.3, 40.0), rings.ringMean(), 1e-3);
    EXPECT_NEAR(rings.filtered(10.3, 0), rings.lateWood(10.3), 0);
}

TEST(RingProfile, SlopeIsTheDerivativeOfTheFilteredProfile) {
    RingProfile rings(5);
    const double w = 0.2, h = 1e-4;
    for (double T : {2.05, 2.5, 2.93, 3.0}) {
        double numeric = (rings.filtered(T + h, w) - rings.filtered(T - h, w)) / (2 * h);
        EXPECT_NEAR(rings.filteredSlope(T, w), numeric, 2e-3 * std::max(1.0, std::abs(numeric)));
    }
}

class StraightTrunkSurface : public ::testing::Test {
protected:
    StraightTrunkSurface() : skeleton_(test::straightTrunk(10, 0.5)), index_(skeleton_) {
        grain_.radialSpeed = 0.004;
        grain_.colour.microAmplitude = 0;
        field_ = std::make_unique<GrowthField>(index_, grain_);
        shader_ = std::make_unique<WoodShader>(*field_);
    }
    Skeleton skeleton_;
    SkeletonIndex index_;
    GrainParams grain_;
    std::unique_ptr<GrowthField> field_;
    std::unique_ptr<WoodShader> shader_;
};

TEST_F(StraightTrunkSurface, GradientIsRadialOverTheRadialSpeed) {
    // T = z / Sa + r / Sb: grad T = (x/r, y/r) / Sb + (0, 0, 1/Sa).
    std::vector<Vec3> points{{0.1, 0, 1}, {0.03, -0.05, 2.5}, {-0.12, 0.07, 4}};
    std::vector<WoodSurfaceSample> out(points.size());
    WoodScratch scratch;
    shader_->evaluateSurface(points, {}, out, scratch);
    for (size_t i = 0; i < points.size(); ++i) {
        const Vec3& p = points[i];
        double r = std::hypot(p.x, p.y);
        Vec3 expected{p.x / r / 0.004, p.y / r / 0.004, 1 / 0.5};
        // Forward differences over 2 % of a ring: the curvature of r costs ~h / (2 r).
        EXPECT_NEAR(length(out[i].gradientT - expected), 0, 0.005 * length(expected));
        // Fibres lie in the ring surface and run up the trunk.
        EXPECT_NEAR(dot(out[i].fibre, normalize(out[i].gradientT)), 0, 1e-9);
        EXPECT_GT(out[i].fibre.z, 0.99);
    }
}

TEST_F(StraightTrunkSurface, FootprintFilterAveragesTheRingsUnderIt) {
    // A footprint along x at (0.1, 0, 1) spans `rings` rings radially; the shader's filtered
    // late-wood share must equal the mean of point samples across it.
    for (double rings : {0.5, 2.0, 7.3}) {
        double w = rings * 0.004;
        SurfaceFootprint f{{w, 0, 0}, {0, 0, 1e-6}, 0, {}};
        Vec3 p{0.1, 0, 1};
        std::vector<WoodSurfaceSample> out(1);
        WoodScratch scratch;
        shader_->evaluateSurface(std::span(&p, 1), std::span(&f, 1), out, scratch);
        EXPECT_NEAR(out[0].ringFilterWidth, rings, 0.01 * rings);
        const int samples = 2000;
        std::vector<Vec3> line(samples);
        for (int i = 0; i < samples; ++i) line[i] = p + Vec3{w * ((i + 0.5) / samples - 0.5), 0, 0};
        std::vector<WoodSurfaceSample> points(samples);
        shader_->evaluateSurface(line, {}, points, scratch);
        double mean = 0;
        for (const auto& s : points) mean += s.lateWood;
        EXPECT_NEAR(out[0].lateWood, mean / samples, 0.01) << rings << " rings";
    }
}

TEST_F(StraightTrunkSurface, IsotropicFootprintDiameterFiltersLikeDifferentials) {
    Vec3 p{0.1, 0, 1};
    SurfaceFootprint along{{0.01, 0, 0}, {0, 0.01, 0}, 0, {}};
    SurfaceFootprint iso{{}, {}, 0.01, {}};
    std::vector<WoodSurfaceSample> a(1), b(1);
    WoodScratch scratch;
    shader_->evaluateSurface(std::span(&p, 1), std::span(&along, 1), a, scratch);
    shader_->evaluateSurface(std::span(&p, 1), std::span(&iso, 1), b, scratch);
    EXPECT_NEAR(a[0].ringFilterWidth, b[0].ringFilterWidth, 0.01 * b[0].ringFilterWidth);
}

// End grain measures darker and redder than side grain (Hirata et al. 2020): the same wood
// seen on a cross cut (normal along the fibre) against a flat-sawn face (normal across it).
TEST_F(StraightTrunkSurface, EndGrainIsDarkerAndRedderThanSideGrain) {
    std::vector<Vec3> points{{0.05, 0.02, 1}};
    const Vec3 up{0, 0, 1}, side{1, 0, 0}, oblique = normalize(Vec3{1, 0, 1});
    auto albedoWith = [&](Vec3 normal) {
        std::vector<SurfaceFootprint> f{{{}, {}, 0.0001, normal}};
        std::vector<WoodSurfaceSample> out(1);
        WoodScratch scratch;
        shader_->evaluateSurface(points, f, out, scratch);
        return out[0].albedo;
    };
    Lab end = labFromLinearSrgb(albedoWith(up)), flat = labFromLinearSrgb(albedoWith(side));
    Lab unknown = labFromLinearSrgb(albedoWith({}));
    Lab between = labFromLinearSrgb(albedoWith(oblique));
    EXPECT_LT(end.L, flat.L - 5);               // about 8-10 L* darker at the defaults
    EXPECT_GT(end.a - end.b, flat.a - flat.b);  // redder: hue towards a*
    EXPECT_NEAR(flat.L, unknown.L, 1e-6);       // side grain and no normal: (almost) no term
    EXPECT_GT(between.L, end.L);                // 45 degrees: a quarter of the term
    EXPECT_LT(between.L, flat.L);
}

TEST_F(StraightTrunkSurface, TheStrongestTextureAGrainAllowsKeepsTheAlbedoAReflectance) {
    // A light wood with cell amplitudes of 0.5 each and end-grain texture 4 (the parser's
    // limits): its end grain's albedo once reached 1.76 and went down to -0.70.
    grain_.colour.earlyWood = grain_.colour.lateWood = {0.9, 0.85, 0.8};
    grain_.colour.endGrainTexture = 4;
    grain_.anatomy.enabled = true;
    grain_.anatomy.fibreAmplitude = grain_.anatomy.speckleAmplitude = 0.5;
    const GrowthField field(index_, grain_);
    const WoodShader shader(field);
    std::vector<Vec3> points;
    for (int k = 0; k < 4000; ++k)
        points.push_back(
            {0.01 + 0.00002 * k * std::cos(0.37 * k), 0.01 + 0.00002 * k * std::sin(0.37 * k), 1});
    std::vector<SurfaceFootprint> f(points.size(), {{}, {}, 0.0001, {0, 0, 1}});
    std::vector<WoodSurfaceSample> out(points.size());
    WoodScratch scratch;
    shader.evaluateSurface(points, f, out, scratch);
    int bright = 0;
    for (const WoodSurfaceSample& o : out)
        for (double c : {o.albedo.r, o.albedo.g, o.albedo.b}) {
            EXPECT_GE(c, 0.0);
            EXPECT_LE(c, 1.0);
            bright += c == 1.0;
        }
    EXPECT_GT(bright, 0) << "the case reaches the bound";
}

// Conifer cells in radial files (speckle drawn out radially) show as such on a quarter-sawn
// face, across the fibre; on end grain they are round (drawn out there they read as grey
// radial fur next to a photograph of hinoki end grain, Mokume H11 B).
TEST_F(StraightTrunkSurface, RadialCellFilesShowOnSideGrainAndRoundCellsOnEndGrain) {
    grain_.anatomy.enabled = true;
    grain_.anatomy.fibreAmplitude = grain_.anatomy.streakAmplitude = grain_.anatomy.ringTone = 0;
    grain_.anatomy.rayWidth = 0;
    grain_.anatomy.speckleAmplitude = 0.3;
    grain_.anatomy.speckleSize = grain_.anatomy.speckleLength = 0.0002;
    grain_.anatomy.speckleRadial = 0.0008;
    grain_.colour.earlyWood = grain_.colour.lateWood = {0.6, 0.45, 0.35};
    const GrowthField field(index_, grain_);
    const WoodShader shader(field);
    // An n x n patch, 40 um a step, of the albedo's red: rows along `rows`, columns along
    // `columns`, the face's normal `normal`, point-sampled (a footprint of 1 um).
    constexpr int n = 80;
    auto patch = [&](const Vec3& centre, const Vec3& rows, const Vec3& columns,
                     const Vec3& normal) {
        std::vector<Vec3> points;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j)
                points.push_back(centre + rows * (0.00004 * (i - n / 2)) +
                                 columns * (0.00004 * (j - n / 2)));
        std::vector<SurfaceFootprint> f(points.size(), {{}, {}, 1e-6, normal});
        std::vector<WoodSurfaceSample> out(points.size());
        WoodScratch scratch;
        shader.evaluateSurface(points, f, out, scratch);
        std::vector<double> v;
        for (const WoodSurfaceSample& o : out) v.push_back(o.albedo.r);
        return v;
    };
    const Vec3 radial{1, 0, 0}, tangential{0, 1, 0}, up{0, 0, 1};
    // End grain at 7 cm from the pith: round cells.
    EXPECT_LT(test::structureTensorRatio(patch({0.07, 0, 1}, radial, tangential, up), n), 1.6);
    // Quarter-sawn (the plane through the pith): cells 4 times as long radially as along the
    // fibre, so the texture changes faster up the trunk than out along the radius.
    double alongRadius = 0, alongFibre = 0;
    const double ratio = test::structureTensorRatio(patch({0.07, 0, 1}, radial, up, tangential), n,
                                                    &alongRadius, &alongFibre);
    EXPECT_GT(ratio, 3);
    EXPECT_GT(alongFibre, 3 * alongRadius);
}

TEST(WoodSurface, FibresBendAroundAKnot) {
    // Beside a horizontal branch the rings wrap around it: the fibre direction there leaves
    // the trunk axis, while far from it it runs straight up.
    ChainProperties props;
    props.gamma = 1;
    Skeleton sk = test::trunkWithBranch(2, {1, 0, 0}, 1.0, props);
    SkeletonIndex index(sk);
    GrainParams g;
    g.radialSpeed = 0.004;
    GrowthField field(index, g);
    WoodShader shader(field);
    std::vector<Vec3> points{{0.06, 0.0, 2.02}, {0.06, 0.0, 3.5}};
    std::vector<WoodSurfaceSample> out(2);
    WoodScratch scratch;
    shader.evaluateSurface(points, {}, out, scratch);
    EXPECT_LT(std::abs(out[0].fibre.z), 0.95);  // bent by the knot
    EXPECT_GT(out[1].fibre.z, 0.999);           // clear wood
}

// Measured latewood shares (skeleton latewood_shares) move each ring's late-wood band: at
// phase 0.7 a ring with half its width in late wood is in late wood, one with a tenth is not.
TEST(WoodSurface, LatewoodSharesMoveTheLateWoodBand) {
    Skeleton trunk = test::straightTrunk(10, 0.5);
    trunk.setRingWidths(std::vector<double>(40, 0.004));
    std::vector<double> shares;
    for (int k = 0; k < 40; ++k) shares.push_back(k % 2 ? 0.5 : 0.1);
    trunk.setLatewoodShares(shares);
    SkeletonIndex index(trunk);
    GrainParams grain;
    grain.radialSpeed = 0.004;
    GrowthField field(index, grain);
    WoodShader shader(field);
    for (int k = 10; k < 14; ++k) {
        std::vector<Vec3> p{{(k + 0.7) * 0.004, 0, 0}};
        std::vector<WoodSurfaceSample> out(1);
        WoodScratch scratch;
        shader.evaluateSurface(p, {}, out, scratch);
        if (k % 2)
            EXPECT_GT(out[0].lateWood, 0.5) << k;
        else
            EXPECT_LT(out[0].lateWood, 0.5) << k;
    }
}

// A knot's ring wobble moves the late wood the shader draws inside the knot, in both of its
// paths (surface and plain colour), and nowhere outside it; T itself is left as it was.
TEST(WoodSurface, KnotRingWobbleMovesTheKnotsLateWoodOnly) {
    ChainProperties props;
    props.gamma = 0.3;
    Skeleton sk = test::trunkWithBranch(2, {1, 0, 0}, 1.0, props);
    SkeletonIndex index(sk);
    GrainParams round, wobbly;
    round.radialSpeed = wobbly.radialSpeed = 0.004;
    wobbly.colour.knotRingWobble = 0.5;
    GrowthField roundField(index, round), wobblyField(index, wobbly);
    WoodShader roundShader(roundField), wobblyShader(wobblyField);
    // Across the branch's section 5 cm out (in the knot), and clear wood far above it.
    std::vector<Vec3> knot, clear;
    for (int i = 0; i < 40; ++i) {
        const double a = 0.3 * i, r = 0.0003 + 0.00012 * i;
        knot.push_back({0.05, r * std::cos(a), 2 + r * std::sin(a)});
        clear.push_back({0.05 + 0.001 * i, 0.0, 3.5});
    }
    auto surface = [](const WoodShader& shader, const std::vector<Vec3>& p) {
        std::vector<WoodSurfaceSample> out(p.size());
        WoodScratch scratch;
        shader.evaluateSurface(p, {}, out, scratch);
        return out;
    };
    auto plain = [](const WoodShader& shader, const std::vector<Vec3>& p) {
        std::vector<WoodSample> out(p.size());
        GrowthScratch scratch;
        std::vector<GrowthSample> samples;
        shader.evaluate(p, out, scratch, samples);
        return out;
    };
    const auto roundKnot = surface(roundShader, knot), wobblyKnot = surface(wobblyShader, knot);
    const auto roundPlain = plain(roundShader, knot), wobblyPlain = plain(wobblyShader, knot);
    int moved = 0, movedPlain = 0;
    for (size_t i = 0; i < knot.size(); ++i) {
        ASSERT_GT(roundKnot[i].knot, 0.75) << i;  // inside the knot
        EXPECT_EQ(wobblyKnot[i].T, roundKnot[i].T) << i;
        moved += std::abs(wobblyKnot[i].lateWood - roundKnot[i].lateWood) > 0.01;
        movedPlain += wobblyPlain[i].albedo != roundPlain[i].albedo;
    }
    EXPECT_GT(moved, 20);
    EXPECT_GT(movedPlain, 20);
    const auto roundClear = surface(roundShader, clear), wobblyClear = surface(wobblyShader, clear);
    for (size_t i = 0; i < clear.size(); ++i) {
        ASSERT_EQ(roundClear[i].knot, 0) << i;
        EXPECT_EQ(wobblyClear[i].lateWood, roundClear[i].lateWood) << i;
        EXPECT_EQ(wobblyClear[i].albedo, roundClear[i].albedo) << i;
    }
}

}  // namespace
}  // namespace nenrin
