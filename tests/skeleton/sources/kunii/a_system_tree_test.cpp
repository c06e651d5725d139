#include "skeleton/sources/kunii/a_system_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "util/input_error.h"

namespace nenrin {
namespace {

constexpr double kDegree = std::numbers::pi / 180;

double angleBetween(const Vec3& a, const Vec3& b) {
    return std::acos(std::clamp(dot(normalize(a), normalize(b)), -1.0, 1.0));
}

TEST(ASystemTree, EveryForkAddsOneAxis) {
    ASystemParams p = aSystemPreset("aono-kunii-b");
    for (int gen = 1; gen <= 8; ++gen) {
        p.generations = gen;
        EXPECT_EQ(growASystem(p).size(), size_t{1} << (gen - 1)) << gen;
    }
}

TEST(ASystemTree, ALongerTrunkCarriesMoreLimbsOfBoundedDepth) {
    ASystemParams p = aSystemPreset("aono-kunii-a");
    p.generations = 4;
    p.trunkForks = 12;
    std::vector<ASystemAxis> axes = growASystem(p);
    // The trunk forks 12 times: 11 limbs, each an A-system of at most generations - 1 forks.
    size_t expected = 1;
    for (int k = 0; k + 1 < p.trunkForks; ++k)
        expected += size_t{1} << (std::min(p.trunkForks - k - 1, p.generations - 1) - 1);
    EXPECT_EQ(axes.size(), expected);
    EXPECT_EQ(axes[0].points.size(), 13u);
    for (const ASystemAxis& a : axes)
        if (a.order >= 1) {
            EXPECT_LE(a.points.size(), static_cast<size_t>(p.generations));
        }
}

TEST(ASystemTree, ContractionRatiosAndBranchingAnglesHoldAtEveryFork) {
    for (const std::string& name : aSystemPresetNames()) {
        ASystemParams p = aSystemPreset(name);
        p.generations = 6;
        std::vector<ASystemAxis> axes = growASystem(p, 1.0);
        for (size_t a = 0; a < axes.size(); ++a) {
            const auto& pts = axes[a].points;
            for (size_t i = 2; i < pts.size(); ++i) {
                Vec3 d0 = pts[i - 1] - pts[i - 2], d1 = pts[i] - pts[i - 1];
                EXPECT_NEAR(length(d1) / length(d0), p.contraction1, 1e-12) << name;
                EXPECT_NEAR(angleBetween(d0, d1), p.branchAngle1 * kDegree, 1e-9) << name;
            }
            if (axes[a].parent < 0) continue;
            const auto& parent = axes[static_cast<size_t>(axes[a].parent)].points;
            size_t k = static_cast<size_t>(axes[a].parentSegment);
            Vec3 parentDir = parent[k + 1] - parent[k];
            Vec3 dir = pts[1] - pts[0];
            EXPECT_EQ(pts[0], parent[k + 1]);  // starts at the fork
            EXPECT_NEAR(length(dir) / length(parentDir), p.contraction2, 1e-12) << name;
            EXPECT_NEAR(angleBetween(parentDir, dir), p.branchAngle2 * kDegree, 1e-9) << name;
        }
    }
}

TEST(ASystemTree, TheBranchingPlaneTurnsByTheDivergenceAngle) {
    for (double divergence : {180.0, 137.5, 90.0}) {
        ASystemParams p = aSystemPreset("aono-kunii-b");
        p.divergenceAngle = divergence;
        p.generations = 7;
        std::vector<ASystemAxis> axes = growASystem(p, 0.0);  // straight vertical trunk
        std::vector<double> azimuths;
        for (const ASystemAxis& a : axes)
            if (a.order == 1) {
                Vec3 d = a.points[1] - a.points[0];
                azimuths.push_back(std::atan2(d.y, d.x));
            }
        ASSERT_EQ(azimuths.size(), 6u);
        for (size_t i = 1; i < azimuths.size(); ++i) {
            double turn = std::remainder(azimuths[i] - azimuths[i - 1], 2 * std::numbers::pi);
            double expected = std::remainder(divergence * kDegree, 2 * std::numbers::pi);
            EXPECT_NEAR(std::abs(turn), std::abs(expected), 1e-9) << divergence;
        }
    }
}

TEST(ASystemTree, StandaloneSkeletonIsValid) {
    ASystemParams p = aSystemPreset("aono-kunii-c");
    Skeleton sk = makeASystemTree(p, 12.0, 0.5, 0.3);
    EXPECT_EQ(sk.chains().size(), size_t{1} << (p.generations - 1));
    EXPECT_NEAR(sk.node(sk.segment(sk.chain(0).segmentCount - 1).to).position.z, 12.0, 1e-9);
    for (const auto& s : sk.segments()) {
        EXPECT_GE(length(sk.end(s) - sk.start(s)), 1e-6);
        EXPECT_GE(sk.node(s.to).birthTime, sk.node(s.from).birthTime);
        if (s.kind == SegmentKind::Branch) {
            EXPECT_NEAR(s.gamma, std::pow(p.widthRatio, s.order), 1e-12);
        }
    }
}

TEST(ASystemTree, BadParametersAndPresetsAreInputErrors) {
    EXPECT_THROW(aSystemPreset("aono-kunii-z"), InputError);
    try {
        aSystemPreset("oak");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("aono-kunii-a"), std::string::npos) << e.what();
    }
    ASystemParams p;
    p.contraction1 = 1.5;
    EXPECT_THROW(growASystem(p), InputError);
    p = ASystemParams{};
    p.branchAngle2 = std::nan("");
    EXPECT_THROW(growASystem(p), InputError);
    p = ASystemParams{};
    p.generations = 0;
    try {
        growASystem(p);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("generations"), std::string::npos) << e.what();
    }
    EXPECT_THROW(makeASystemTree(ASystemParams{}, -1), InputError);
}

}  // namespace
}  // namespace nenrin
