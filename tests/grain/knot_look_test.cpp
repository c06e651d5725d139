// Knot geometry and look: the knot's section radius the field reports is the edge one sees,
// for live and dead knots, and a dead knot's bark ring is the stated width all round, ending
// at that edge; the core is darker than the edge and the ring is filtered over a footprint.

#include "grain/knot_look.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "grain/grain_params.h"
#include "grain/growth_field.h"
#include "grain/wood_colour.h"
#include "skeleton/skeleton_index.h"
#include "tests/test_trees.h"
#include "util/hash.h"
#include "util/input_error.h"

namespace nenrin {
namespace {

// A horizontal branch leaving a vertical trunk at 2 m, births by Sa = 0.5 m/year.
constexpr double kHeight = 2, kSa = 0.5;

Skeleton branchTree(double deathTime) {
    ChainProperties props;
    props.gamma = 0.3;
    props.deathTime = deathTime;
    props.diebackExponent = 4;
    return test::trunkWithBranch(kHeight, {1, 0, 0}, 1.0, props, 10, kSa);
}

/// A cross-section of the branch `x` m out from the trunk's axis: points on a ray at azimuth
/// phi about the branch, from its axis outward.
Vec3 onRay(double x, double phi, double r) {
    return {x, r * std::cos(phi), kHeight + r * std::sin(phi)};
}

/// Along the ray from `axis` (a point of the branch's axis) in direction `ray`: where the
/// branch's share of the blend crosses one half.
double edgeOnRay(const GrowthField& field, const Vec3& axis, const Vec3& ray) {
    double lo = 0, hi = 0.05;
    for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (field.evaluate(axis + ray * mid).knot > 0.5 ? lo : hi) = mid;
    }
    return lo;
}

/// The same on a ray about the level branch of branchTree.
double visibleEdge(const GrowthField& field, double x, double phi) {
    return edgeOnRay(field, onRay(x, phi, 0), onRay(x, phi, 1) - onRay(x, phi, 0));
}

GrowthField makeField(const SkeletonIndex& index) {
    GrainParams grain;
    grain.junction.p = 4;
    return GrowthField(index, grain);
}

// Near its edge the reported radius is the edge one sees; from the middle of the knot it is
// a few per cent off, because the edge's time is taken from the trunk's time at P.
void expectRadiusIsVisibleEdge(const GrowthField& field, bool dead) {
    for (double x : {0.04, 0.06}) {
        for (int a = 0; a < 12; ++a) {
            const double phi = 2 * std::numbers::pi * a / 12;
            const double edge = visibleEdge(field, x, phi);
            GrowthSample near = field.evaluate(onRay(x, phi, 0.95 * edge));
            ASSERT_EQ(near.knotChain, 1);
            EXPECT_EQ(near.knotDied, dead);
            EXPECT_NEAR(near.knotRadius, edge, 0.01 * edge) << "x " << x << " azimuth " << a;
            EXPECT_NEAR(near.knotAxisDistance, 0.95 * edge, 1e-12);
            EXPECT_NEAR(length(near.knotOffset), near.knotAxisDistance, 1e-12);
            GrowthSample mid = field.evaluate(onRay(x, phi, 0.5 * edge));
            EXPECT_NEAR(mid.knotRadius, edge, 0.06 * edge) << "x " << x << " azimuth " << a;
        }
    }
}

TEST(KnotLook, LiveKnotRadiusIsTheVisibleEdge) {
    Skeleton sk = branchTree(kNeverDies);
    SkeletonIndex index(sk);
    expectRadiusIsVisibleEdge(makeField(index), false);
}

TEST(KnotLook, DeadKnotRadiusIsTheVisibleEdge) {
    Skeleton sk = branchTree(8);
    SkeletonIndex index(sk);
    expectRadiusIsVisibleEdge(makeField(index), true);
}

TEST(KnotLook, DeadKnotBarkRingIsItsStatedWidthAllRound) {
    Skeleton sk = branchTree(8);
    SkeletonIndex index(sk);
    GrowthField field = makeField(index);
    const ColourParams& c = field.params().colour;
    const double x = 0.05, step = 2e-5;
    for (int a = 0; a < 16; ++a) {
        const double phi = 2 * std::numbers::pi * a / 16;
        double ring = 0, last = -1;
        for (double r = 0; r < 0.02; r += step) {
            KnotLook look = knotLook(field.evaluate(onRay(x, phi, r)), c);
            if (look.rim > 0.5) ring += step, last = r;
        }
        EXPECT_NEAR(ring, c.deadKnotRimWidth, 0.1 * c.deadKnotRimWidth) << "azimuth " << a;
        EXPECT_NEAR(last, visibleEdge(field, x, phi), 0.05 * c.deadKnotRimWidth) << "azimuth " << a;
    }
}

TEST(KnotLook, CoreIsDarkerThanTheEdgeAndClearWoodIsUntouched) {
    ColourParams c;
    GrowthSample clear;
    EXPECT_EQ(knotLook(clear, c).darkening, 0);
    GrowthSample s;
    s.knot = 1;
    s.knotChain = 3;
    s.knotRadius = 0.006;
    s.knotAxisDirection = {1, 0, 0};
    s.knotAxisDistance = 0;
    const double pith = knotLook(s, c).darkening;
    s.knotAxisDistance = 0.0059;
    const double edge = knotLook(s, c).darkening;
    EXPECT_NEAR(pith - edge, c.knotCore, 0.01);
    EXPECT_NEAR(edge, c.knotDarkening, 0.01);
    EXPECT_EQ(knotLook(s, c).rim, 0);  // a live knot has no bark ring
}

// Knot wood's late wood is darker by ring_darkening x E; early wood (E = 0) and clear wood are
// as without it.
TEST(KnotLook, RingDarkeningDarkensTheKnotsLateWoodOnly) {
    ColourParams plain, ringed;
    plain.heartwood = ringed.heartwood = false;
    ringed.knotRingDarkening = 0.4;
    GrowthSample s;
    s.T = 5.5;
    s.knot = 1;
    s.knotChain = 3;
    s.knotRadius = 0.006;
    s.knotAxisDirection = {1, 0, 0};
    s.knotAxisDistance = 0.003;
    const Vec3 p{0.1, 0, 1};
    for (double e : {0.0, 0.5, 1.0}) {
        const Rgb a = woodColour(s, p, plain, e, 0), b = woodColour(s, p, ringed, e, 0);
        EXPECT_NEAR(b.g, a.g * (1 - 0.4 * e), 1e-12) << "E " << e;
    }
    GrowthSample clear;
    clear.T = 5.5;
    EXPECT_EQ(woodColour(clear, p, plain, 1, 0).g, woodColour(clear, p, ringed, 1, 0).g);
}

// A footprint wider than the ring spreads it: its coverage integrates to the ring's width.
TEST(KnotLook, BarkRingIsFilteredOverTheFootprint) {
    ColourParams c;
    GrowthSample s;
    s.knot = s.deadKnot = 0.4;
    s.knotDied = true;
    s.knotChain = 1;
    s.knotRadius = 0.006;
    s.knotAxisDirection = {1, 0, 0};
    const double footprint = 0.004, step = 1e-5;
    double sharp = 0, filtered = 0, peak = 0;
    for (double r = 0; r < 0.02; r += step) {
        s.knotAxisDistance = r;
        s.knotOffset = {0, r, 0};
        sharp += knotLook(s, c).rim * step;
        double f = knotLook(s, c, footprint).rim;
        filtered += f * step;
        peak = std::max(peak, f);
    }
    EXPECT_NEAR(sharp, c.deadKnotRimWidth, 2 * step);
    EXPECT_NEAR(filtered, c.deadKnotRimWidth, 2 * step);
    EXPECT_NEAR(peak, c.deadKnotRimWidth / footprint, 0.01);
}

// The halo round a knot (colour.knots.halo_*): full at the knot's edge, reaching between half
// and one and a half widths out across the stem (its patches), three times that along it; the
// knot's own wood keeps its own tint, and a white halo leaves the wood as it was.
TEST(KnotLook, HaloReachesItsWidthAcrossTheStemAndFartherAlongIt) {
    Skeleton sk = branchTree(kNeverDies);
    SkeletonIndex index(sk);
    const GrowthField field = makeField(index);
    ColourParams c;
    c.heartwood = false;
    c.knotHaloTint = {0.7, 0.5, 0.4};
    c.knotHaloWidth = 0.004;
    c.knotHaloAxial = 3;
    const double w = c.knotHaloWidth;
    auto haloAt = [&](double x, double phi, double r) {
        const Vec3 p = onRay(x, phi, r);
        return knotHalo(field.evaluate(p), p, c);
    };
    // Along the stem (the trunk is vertical) and across it, on both sides.
    double alongSum = 0, acrossSum = 0;
    for (double x : {0.03, 0.04, 0.05, 0.06, 0.07}) {
        for (double phi : {0.0, std::numbers::pi}) {
            const double edge = visibleEdge(field, x, phi);
            EXPECT_EQ(haloAt(x, phi, 0.9 * edge), 1) << "x " << x;
            EXPECT_GT(haloAt(x, phi, edge + 0.45 * w), 0) << "x " << x;
            EXPECT_EQ(haloAt(x, phi, edge + 1.55 * w), 0) << "x " << x;
            for (double r = edge; r < edge + 2 * w; r += w / 100) acrossSum += haloAt(x, phi, r);
        }
        for (double phi : {0.5 * std::numbers::pi, 1.5 * std::numbers::pi}) {
            const double edge = visibleEdge(field, x, phi);
            EXPECT_GT(haloAt(x, phi, edge + 1.45 * w), 0) << "x " << x;
            EXPECT_EQ(haloAt(x, phi, edge + 4.6 * w), 0) << "x " << x;
            for (double r = edge; r < edge + 6 * w; r += w / 100) alongSum += haloAt(x, phi, r);
        }
    }
    EXPECT_GT(alongSum / acrossSum, 2.0);
    EXPECT_LT(alongSum / acrossSum, 4.5);
    // The knot's own wood (its share past the tint's smoothstep) is not tinted by the halo; the
    // stem just outside the edge is, by the tint; a white halo changes nothing.
    ColourParams white = c;
    white.knotHaloTint = {1, 1, 1};
    const double edge = visibleEdge(field, 0.05, 0);
    const Vec3 inside = onRay(0.05, 0, 0.3 * edge), outside = onRay(0.05, 0, edge + 0.1 * w);
    const GrowthSample in = field.evaluate(inside), out = field.evaluate(outside);
    ASSERT_GE(in.knot, 0.75);
    EXPECT_EQ(woodColour(in, inside, c, 0.5, 0).b, woodColour(in, inside, white, 0.5, 0).b);
    const Rgb tinted = woodColour(out, outside, c, 0.5, 0),
              plain = woodColour(out, outside, white, 0.5, 0);
    const double weight = (1 - knotLook(out, c).tint) * knotHalo(out, outside, c);
    EXPECT_GT(weight, 0.5);
    EXPECT_NEAR(tinted.b, plain.b * (1 - weight * (1 - 0.4)), 1e-12);
    GrowthSample clear;
    clear.T = 5.5;
    EXPECT_EQ(knotHalo(clear, outside, c), 0);
}

// A branch rising at 45 degrees: its cross-section holds the stem's direction only in part,
// and the halo is stretched along that part as much as about a level branch.
TEST(KnotLook, HaloOfASlantingBranchIsStretchedAlongTheStemToo) {
    const Vec3 up = normalize(Vec3{1, 0, 1});
    ChainProperties props;
    props.gamma = 0.3;
    Skeleton sk = test::trunkWithBranch(kHeight, up, 1.0, props, 10, kSa);
    SkeletonIndex index(sk);
    const GrowthField field = makeField(index);
    ColourParams c;
    c.knotHaloTint = {0.7, 0.5, 0.4};
    c.knotHaloWidth = 0.004;
    c.knotHaloAxial = 3;
    // In the branch's cross-section: the stem's direction as seen there, and across it.
    const Vec3 stem = normalize(Vec3{-1, 0, 1}), across{0, 1, 0};
    double alongSum = 0, acrossSum = 0;
    for (double out : {0.05, 0.07, 0.09}) {
        const Vec3 axis = Vec3{0, 0, kHeight} + up * out;
        for (const Vec3& ray : {stem, stem * -1.0, across, across * -1.0}) {
            const double lo = edgeOnRay(field, axis, ray);  // the knot's visible edge
            const bool alongStem = std::abs(dot(ray, stem)) > 0.5;
            for (double r = lo; r < lo + 6 * c.knotHaloWidth; r += c.knotHaloWidth / 100) {
                const Vec3 p = axis + ray * r;
                (alongStem ? alongSum : acrossSum) += knotHalo(field.evaluate(p), p, c);
            }
        }
    }
    ASSERT_GT(acrossSum, 0);
    EXPECT_GT(alongSum / acrossSum, 2.0);
}

// The halo's keys are written back as read, and out of range they are refused.
TEST(KnotLook, HaloKeysRoundTripThroughTheGrainFile) {
    GrainParams g;
    g.colour.knotHaloTint = {0.69, 0.5, 0.36};
    g.colour.knotHaloWidth = 0.012;
    g.colour.knotHaloAxial = 2.5;
    const GrainParams back = parseGrain(grainToJson(g), "g.json");
    EXPECT_EQ(back.colour.knotHaloTint, g.colour.knotHaloTint);
    EXPECT_EQ(back.colour.knotHaloWidth, 0.012);
    EXPECT_EQ(back.colour.knotHaloAxial, 2.5);
    nlohmann::json bad = grainToJson(g);
    bad["colour"]["knots"]["halo_axial"] = 0.5;
    EXPECT_THROW(parseGrain(bad, "g.json"), InputError);
    bad = grainToJson(g);
    bad["colour"]["knots"]["halo_tint"] = {0.5, 1.5, 0.5};
    EXPECT_THROW(parseGrain(bad, "g.json"), InputError);
}

// A knot's rings wobble: inside the knot the ring profile is read at T moved by a value noise
// of ring_wobble_scale, by at most ring_wobble years and by a good share of it on average;
// outside the knot (and with the wobble 0) not at all. The keys round-trip.
TEST(KnotLook, RingWobbleMovesTheRingsInsideTheKnotOnly) {
    ColourParams c;
    c.knotRingWobble = 0.5;
    c.knotRingWobbleScale = 0.006;
    GrowthSample inside;
    inside.T = 7;
    inside.knot = 1;
    GrowthSample outside = inside;
    outside.knot = 0.4;  // under the tint's weight
    double sum2 = 0, largest = 0, near2 = 0, far = 0, farA2 = 0, farB2 = 0;
    const int n = 4000;
    SplitMix rng(3);
    for (int i = 0; i < n; ++i) {
        const Vec3 p{0.03 * rng.uniform(), 0.03 * rng.uniform(), 2 + 0.03 * rng.uniform()};
        const double w = knotRingWobble(inside, p, c);
        EXPECT_DOUBLE_EQ(colourTime(inside, p, c), 7 + w);
        EXPECT_EQ(knotRingWobble(outside, p, c), 0);
        sum2 += w * w;
        largest = std::max(largest, std::abs(w));
        // A tenth of the scale away it has barely moved; five scales away it is another draw.
        const double dNear = knotRingWobble(inside, p + Vec3{0.0006, 0, 0}, c) - w;
        near2 += dNear * dNear;
        const double wFar = knotRingWobble(inside, p + Vec3{0.03, 0.01, 0}, c);
        far += w * wFar, farA2 += w * w, farB2 += wFar * wFar;
    }
    const double rms = std::sqrt(sum2 / n);
    EXPECT_LE(largest, 0.5);
    EXPECT_GT(largest, 0.25);
    EXPECT_GT(rms, 0.05);
    EXPECT_LT(rms, 0.3);
    EXPECT_LT(std::sqrt(near2 / n), 0.3 * rms);
    EXPECT_LT(std::abs(far) / std::sqrt(farA2 * farB2), 0.2);
    c.knotRingWobble = 0;
    EXPECT_EQ(knotRingWobble(inside, {0.01, 0.01, 2}, c), 0);

    GrainParams g;
    g.colour.knotRingWobble = 0.5;
    g.colour.knotRingWobbleScale = 0.006;
    const GrainParams back = parseGrain(grainToJson(g), "g.json");
    EXPECT_EQ(back.colour.knotRingWobble, 0.5);
    EXPECT_EQ(back.colour.knotRingWobbleScale, 0.006);
    nlohmann::json bad = grainToJson(g);
    bad["colour"]["knots"]["ring_wobble_scale"] = 0;
    EXPECT_THROW(parseGrain(bad, "g.json"), InputError);
}

}  // namespace
}  // namespace nenrin
