#include "grain/growth_field.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "grain/field_segment.h"
#include "grain/growth_terms.h"
#include "skeleton/skeleton_file.h"
#include "skeleton/synthetic_tree.h"
#include "tests/test_trees.h"

namespace nenrin {
namespace {

constexpr double kSa = 0.5, kSb = 0.004;

GrainParams plainGrain() {
    GrainParams g;
    g.radialSpeed = kSb;
    return g;
}

/// Radius along `dir` from `centre` at which T crosses `years` (bisection; T increasing).
double ringRadius(const GrowthField& f, Vec3 centre, Vec3 dir, double years, double rMax = 1) {
    double lo = 0, hi = rMax;
    for (int i = 0; i < 200; ++i) {
        double mid = 0.5 * (lo + hi);
        (f.evaluate(centre + dir * mid).T < years ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

TEST(GrowthField, StraightTrunkRingsAreAnalytic) {
    Skeleton sk = test::straightTrunk(10, kSa);
    SkeletonIndex index(sk);
    GrowthField f(index, plainGrain());
    for (double z : {0.5, 2.0, 7.25})
        for (int k = 20; k <= 40; k += 5) {
            double expected = (k - z / kSa) * kSb;  // ring k at (k - z/Sa) Sb
            double r = ringRadius(f, {0, 0, z}, normalize(Vec3{1, 0.3, 0}), k);
            EXPECT_NEAR(r, expected, 1e-6) << "z " << z << " ring " << k;
        }
    // T itself: Ta + Tb exactly.
    GrowthSample s = f.evaluate({0.03, -0.04, 3});
    EXPECT_NEAR(s.T, 3 / kSa + 0.05 / kSb, 1e-9);
    EXPECT_NEAR(s.Ta, 6, 1e-12);
    EXPECT_EQ(s.knot, 0);
}

TEST(GrowthField, DirectionGivesWiderRingsOnTheSunSide) {
    Skeleton sk = test::straightTrunk(10, kSa);
    SkeletonIndex index(sk);
    GrainParams g = plainGrain();
    const double eps = 0.25;
    g.direction.strength = eps;
    g.direction.sunRay = {0, 1, 0};  // the sun stands at -Y
    GrowthField f(index, g);
    Vec3 c{0, 0, 2};
    double sun = ringRadius(f, c, {0, -1, 0}, 31) - ringRadius(f, c, {0, -1, 0}, 30);
    double shade = ringRadius(f, c, {0, 1, 0}, 31) - ringRadius(f, c, {0, 1, 0}, 30);
    EXPECT_NEAR(sun / shade, (1 + eps) / (1 - eps), 1e-5);
}

TEST(GrowthField, AgeNarrowsRingsOutward) {
    Skeleton sk = test::straightTrunk(10, kSa);
    SkeletonIndex index(sk);
    GrainParams g = plainGrain();
    const double delta = 1.4;
    g.age.delta = delta;
    GrowthField f(index, g);
    for (int k : {1, 4, 9, 16, 30})  // at the base Ta = 0: ring k at Sb k^(1/delta)
        EXPECT_NEAR(ringRadius(f, {0, 0, 0}, {1, 0, 0}, k), kSb * std::pow(k, 1 / delta), 1e-6);
}

TEST(GrowthField, TaperWidensRingsLowOnTheTrunk) {
    Skeleton sk = test::straightTrunk(10, kSa);
    SkeletonIndex index(sk);
    GrainParams g = plainGrain();
    g.taper.nu = 0.8;
    g.taper.omega = 0.85;
    GrowthField f(index, g);
    auto width = [&](double z) {
        Vec3 c{0, 0, z};
        double k = z / kSa + 10;
        return ringRadius(f, c, {1, 0, 0}, k + 1) - ringRadius(f, c, {1, 0, 0}, k);
    };
    double low = width(0.5), mid = width(3), high = width(8);
    EXPECT_GT(low, mid);
    EXPECT_GT(mid, high);
    EXPECT_NEAR(low, kSb * (1 + 0.8 * std::pow(0.85, 1.0)), 1e-6);  // Ta = 1 year at 0.5 m
}

/// Knot radius: distance from the branch axis (perpendicular, upwards) where the branch share of
/// the blend falls to one half.
double knotRadius(const GrowthField& f, Vec3 axisPoint, Vec3 up) {
    double lo = 0, hi = 0.2;
    for (int i = 0; i < 60; ++i) {
        double mid = 0.5 * (lo + hi);
        (f.evaluate(axisPoint + up * mid).knot > 0.5 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

TEST(GrowthField, DeadBranchKnotStopsWidening) {
    // A horizontal branch from 2 m; at distance s from the pith the trunk reaches it at
    // T1 = 4 + s / Sb years. The dead branch dies at Tlim = 14 (s = 4 cm).
    Vec3 dir{1, 0, 0};
    ChainProperties live{0.5, kNeverDies, 0};
    ChainProperties dead{0.5, 14.0, 3.0};
    Skeleton skLive = test::trunkWithBranch(2, dir, 1.0, live, 10, kSa);
    Skeleton skDead = test::trunkWithBranch(2, dir, 1.0, dead, 10, kSa);
    SkeletonIndex iLive(skLive), iDead(skDead);
    GrowthField fLive(iLive, plainGrain()), fDead(iDead, plainGrain());
    Vec3 up{0, 0, 1};
    double liveGrowth = knotRadius(fLive, {0.12, 0, 2}, up) - knotRadius(fLive, {0.06, 0, 2}, up);
    double deadGrowth = knotRadius(fDead, {0.12, 0, 2}, up) - knotRadius(fDead, {0.06, 0, 2}, up);
    EXPECT_GT(liveGrowth, 0.004);              // a living knot is a widening cone
    EXPECT_LT(deadGrowth, 0.25 * liveGrowth);  // a dead one is nearly a cylinder
    // While both branches lived the knots were the same.
    EXPECT_NEAR(knotRadius(fLive, {0.02, 0, 2}, up), knotRadius(fDead, {0.02, 0, 2}, up), 1e-4);
    EXPECT_GT(fDead.evaluate({0.12, 0, 2.001}).deadKnot, 0.5);
    EXPECT_EQ(fLive.evaluate({0.12, 0, 2.001}).deadKnot, 0);
}

/// Largest |T(x_{i+1}) - T(x_i)| along a line sampled every `step` metres.
double largestJump(const GrowthField& f, Vec3 from, Vec3 to, double step) {
    int n = static_cast<int>(length(to - from) / step);
    double prev = f.evaluate(from).T, worst = 0;
    for (int i = 1; i <= n; ++i) {
        double t = f.evaluate(lerp(from, to, double(i) / n)).T;
        worst = std::max(worst, std::abs(t - prev));
        prev = t;
    }
    return worst;
}

TEST(GrowthField, ContinuousAcrossJointRegionsOfEquation4) {
    // A trunk bent by 30 degrees at 2 m: lines across the slab planes of both segments on the
    // concave (region D) and convex (region C) sides.
    Skeleton sk;
    double a = 30 * std::numbers::pi / 180;
    Vec3 q{0, 0, 2}, top = q + Vec3{std::sin(a), 0, std::cos(a)} * 3;
    sk.addTrunk({{0, 0, 0}, q, top}, {0, 2 / kSa, 5 / kSa});
    SkeletonIndex index(sk);
    GrowthField f(index, plainGrain());
    const double step = 2e-5;  // |grad T| = 1/Sb = 250 years/m: 0.005 years per step
    for (double x : {-0.08, -0.03, 0.03, 0.08}) {
        double jump = largestJump(f, {x, 0.01, 1.8}, {x, 0.01, 2.25}, step);
        EXPECT_LT(jump, 0.008) << "x " << x;
    }
}

TEST(GrowthField, ContinuousAcrossTheJunctionPlaneOfEquation5) {
    Vec3 dir = normalize(Vec3{1, 0, 0.7});
    Skeleton sk = test::trunkWithBranch(2, dir, 1.5, {0.5, kNeverDies, 0}, 10, kSa);
    SkeletonIndex index(sk);
    GrowthField f(index, plainGrain());
    // Vertical lines beside the branch cross plane F (perpendicular to the branch, through its
    // start) and the reach fade; a horizontal one runs through the knot.
    for (double x : {0.02, 0.05, 0.1}) {
        double jump = largestJump(f, {x, 0.004, 1.85}, {x, 0.004, 2.3}, 2e-5);
        EXPECT_LT(jump, 0.008) << "x " << x;
    }
    EXPECT_LT(largestJump(f, {-0.1, 0.003, 2.05}, {0.15, 0.003, 2.05}, 2e-5), 0.008);
    // And the branch is really there: a knot, earlier growth time than the trunk path.
    GrowthSample inKnot = f.evaluate(Vec3{0, 0, 2} + dir * 0.08);
    EXPECT_GT(inKnot.knot, 0.9);
    EXPECT_LT(inKnot.T, inKnot.trunkTime);
}

// The field against the named terms of growth_terms.h, where they must agree: eq. 1-4 written
// out for the members of a bent trunk (regions A, C and D of Fig. 3).
TEST(GrowthField, TrunkPathIsEquations1To4) {
    Skeleton sk;
    const double a = 30 * std::numbers::pi / 180;
    const Vec3 q{0, 0, 2}, up{std::sin(a), 0, std::cos(a)};
    sk.addTrunk({{0, 0, 0}, q, q + up * 3}, {0, 2 / kSa, 5 / kSa});
    SkeletonIndex index(sk);
    GrowthField f(index, plainGrain());
    // Eq. 1-3 through each member: Ta = Da / Sa along the path, Tb = Db / Sb.
    struct Member {
        double time, planeDistance;  // M: distance to the plane through q perpendicular to it
    };
    auto lower = [&](const Vec3& p) {
        const Vec3 n{0, 0, p.z};
        return Member{p.z / kSa + length(p - n) / kSb, 2 - p.z};
    };
    auto upper = [&](const Vec3& p) {
        const double u = dot(p - q, up);
        return Member{(2 + u) / kSa + length(p - (q + up * u)) / kSb, u};
    };
    // Region D, on the concave side of the bend: in both slabs, eq. 4.
    int blended = 0;
    for (const Vec3& p : {Vec3{0.06, 0.01, 1.99}, Vec3{0.1, -0.02, 1.97}, Vec3{0.03, 0, 1.995}}) {
        const Member m1 = lower(p), m2 = upper(p);
        ASSERT_GT(m1.planeDistance, 0);
        ASSERT_GT(m2.planeDistance, 0);
        const double eq4 = (m1.time * m1.planeDistance + m2.time * m2.planeDistance) /
                           (m1.planeDistance + m2.planeDistance);
        EXPECT_NEAR(f.evaluate(p).trunkTime, eq4, 1e-9 * eq4) << p.x;
        blended += std::abs(eq4 - m1.time) > 1e-3 && std::abs(eq4 - m2.time) > 1e-3;
    }
    EXPECT_EQ(blended, 3);  // the blend is neither member's own time there
    // Region A (one slab): the member's own time; region C (convex side, beyond both slabs):
    // the path through the joint q.
    const Vec3 inA{0.04, 0.02, 1.2}, inC{-0.05, 0.01, 2.01};
    EXPECT_NEAR(f.evaluate(inA).trunkTime, lower(inA).time, 1e-9 * lower(inA).time);
    EXPECT_NEAR(f.evaluate(inC).trunkTime, 2 / kSa + length(inC - q) / kSb, 1e-9 * 10);
}

// Eq. 5 at a junction of one branch with weight 1: the field's smooth minimum over all branch
// paths is junctionBlend there, bit for bit; and the branch path is eq. 2-3' with gamma.
TEST(GrowthField, OneBranchJunctionIsEquation5) {
    const Vec3 dir = normalize(Vec3{1, 0, 0.7});
    const double gamma = 0.5;
    Skeleton sk = test::trunkWithBranch(2, dir, 1.5, {gamma, kNeverDies, 0}, 10, kSa);
    SkeletonIndex index(sk);
    const GrainParams grain = plainGrain();
    GrowthField f(index, grain);
    const std::vector<FieldSegment> segments = flattenSegments(sk);
    ASSERT_EQ(segments.size(), 3u);
    const FieldSegment& branch = segments[2];  // the branch's only segment, Q = (0, 0, 2)
    ASSERT_TRUE(branch.branch);
    int knotted = 0;
    for (double along : {0.02, 0.05, 0.1})
        for (double off : {0.002, 0.006, 0.015}) {
            const Vec3 p = branch.a + dir * along + Vec3{0, off, 0};
            const GrowthSample g = f.evaluate(p);
            EXPECT_NEAR(g.trunkTime, p.z / kSa + std::hypot(p.x, p.y) / kSb, 1e-9 * g.trunkTime);
            const GrowthField::PathTime path = f.chainPathTime(2, p);
            const double t2 = (2 + along) / kSa + off / (gamma * kSb);
            EXPECT_NEAR(path.T, t2, 1e-9 * t2);
            const Vec3 v = p - branch.a;
            const double sinAlpha = dot(v, branch.axis) / length(v);
            ASSERT_EQ(junctionReachWeight(path.T / sinAlpha, g.trunkTime, grain.junction.reach), 1);
            EXPECT_EQ(g.T, junctionBlend(g.trunkTime, path.T, sinAlpha, grain.junction.p))
                << along << " " << off;
            // p = 2: the paper's form T1 T2 / sqrt(T2^2 + (T1 sin alpha)^2).
            const double t1 = g.trunkTime;
            EXPECT_NEAR(g.T, t1 * path.T / std::hypot(path.T, t1 * sinAlpha), 1e-9 * t1);
            knotted += g.knot > 0.5;
        }
    EXPECT_GT(knotted, 5);
    // Behind plane F the trunk path alone.
    const GrowthSample behind = f.evaluate({-0.03, 0.01, 1.97});
    EXPECT_EQ(behind.T, behind.trunkTime);
    EXPECT_EQ(behind.knot, 0);
}

TEST(GrowthField, BatchAndSingleEvaluationAreBitwiseEqual) {
    // Batching must never change an answer: one point at a time, a 32 x 32 batch listed row by
    // row (chunks of two long rows), and the same batch listed as 8 x 8 chunks give the same
    // bits, with either index. Branches of 25 segments, and of 400 (a chunk then meets a branch
    // in many segments, and each quarter of it gets its own narrower list).
    for (size_t perBranch : {25, 400}) {
        SyntheticTreeOptions o;
        o.segmentsPerBranch = perBranch;
        o.totalSegments = 200 + 240 * perBranch;
        Skeleton sk = makeSyntheticTree(o);
        SkeletonIndex embree(sk, IndexBackend::Embree), brute(sk, IndexBackend::BruteForce);
        GrainParams g = plainGrain();
        g.sway.amplitude = 0.002;
        g.sway.radialJitter = 0.05;
        g.direction.strength = 0.1;
        GrowthField fe(embree, g), fb(brute, g);
        int knotted = 0;
        for (double z : {4.0, 9.5, 15.0}) {
            std::vector<Vec3> rows, chunks;
            for (int j = 0; j < 32; ++j)
                for (int i = 0; i < 32; ++i)
                    rows.push_back({-0.12 + 0.0075 * i, -0.12 + 0.0075 * j, z});
            for (int cj = 0; cj < 32; cj += 8)
                for (int ci = 0; ci < 32; ci += 8)
                    for (int j = cj; j < cj + 8; ++j)
                        for (int i = ci; i < ci + 8; ++i) chunks.push_back(rows[j * 32 + i]);
            std::vector<GrowthSample> byRows(rows.size()), byChunks(chunks.size());
            GrowthScratch scratch;
            fe.evaluateBatch(rows, byRows, scratch);
            fb.evaluateBatch(chunks, byChunks, scratch);
            for (size_t c = 0; c < chunks.size(); ++c) {
                size_t i = static_cast<size_t>(std::lround((chunks[c].y + 0.12) / 0.0075) * 32 +
                                               std::lround((chunks[c].x + 0.12) / 0.0075));
                ASSERT_EQ(byChunks[c].T, byRows[i].T) << "z " << z << " point " << i;
                ASSERT_EQ(byChunks[c].knot, byRows[i].knot);
            }
            for (size_t i = 0; i < rows.size(); i += 7) {
                GrowthSample single = fe.evaluate(rows[i]);
                ASSERT_EQ(single.T, byRows[i].T) << "z " << z << " point " << i;
                ASSERT_EQ(single.knot, byRows[i].knot);
                knotted += single.knot > 0;
            }
        }
        EXPECT_GT(knotted, 10) << perBranch;  // the batches do meet branches
    }
}

TEST(GrowthField, AScratchCopiedOrMovedStillServes) {
    Vec3 dir = normalize(Vec3{1, 0, 0.7});
    Skeleton sk = test::trunkWithBranch(2, dir, 1.5, {0.5, kNeverDies, 0}, 10, kSa);
    SkeletonIndex index(sk);
    GrowthField f(index, plainGrain());
    std::vector<Vec3> points;
    for (int i = 0; i < 100; ++i) points.push_back(Vec3{0, 0, 2} + dir * (0.001 * i));
    std::vector<GrowthSample> a(points.size()), b(points.size()), c(points.size());
    GrowthScratch used;
    f.evaluateBatch(points, a, used);
    GrowthScratch copy(used), moved(std::move(used));
    f.evaluateBatch(points, b, copy);
    f.evaluateBatch(points, c, moved);
    used = copy;  // a moved-from scratch may be assigned again, and serves again
    f.evaluateBatch(points, c, used);
    for (size_t i = 0; i < points.size(); ++i) {
        ASSERT_EQ(a[i].T, b[i].T);
        ASSERT_EQ(a[i].T, c[i].T);
        ASSERT_EQ(a[i].knot, c[i].knot);
    }
    EXPECT_GT(a[50].knot, 0.5);
}

TEST(GrowthField, BundledConiferHasLiveAndDeadKnots) {
    Skeleton sk =
        loadSkeletonFile(std::string(NENRIN_SOURCE_DIR) + "/scenes/skeletons/conifer.json");
    SkeletonIndex index(sk);
    GrowthField f(index, plainGrain());
    int live = 0, dead = 0;
    for (uint32_t c = 1; c < sk.chains().size(); ++c) {
        const auto& s = sk.segment(sk.chain(c).firstSegment);
        Vec3 p = lerp(sk.start(s), sk.end(s), 0.08 / length(sk.end(s) - sk.start(s)));
        GrowthSample g = f.evaluate(p + Vec3{0, 0, 0.002});
        if (g.knot > 0.5) (g.deadKnot > 0.5 ? dead : live)++;
    }
    EXPECT_GT(live, 5);
    EXPECT_GT(dead, 5);
}

}  // namespace
}  // namespace nenrin
