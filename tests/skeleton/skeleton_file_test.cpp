#include "skeleton/skeleton_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "util/json_reader.h"

namespace nenrin {
namespace {

Skeleton parse(const std::string& text) {
    return parseSkeleton(parseJsonText(text, "s.json"), "s.json");
}

std::string errorOf(const std::string& text) {
    try {
        parse(text);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(SkeletonFile, TrunkBirthTimesFollowElongationSpeed) {
    Skeleton s =
        parse(R"({"elongation_speed": 0.5, "trunk": {"points": [[0,0,0],[0,0,2],[0,0,5]]}})");
    ASSERT_EQ(s.chains().size(), 1u);
    ASSERT_EQ(s.segments().size(), 2u);
    EXPECT_DOUBLE_EQ(s.node(1).birthTime, 4.0);
    EXPECT_DOUBLE_EQ(s.node(2).birthTime, 10.0);
    EXPECT_EQ(s.segment(0).next, 1);
    EXPECT_EQ(s.segment(1).previous, 0);
}

TEST(SkeletonFile, BranchByHeightAzimuthElevation) {
    Skeleton s = parse(R"({"elongation_speed": 1, "trunk": {"points": [[0,0,0],[0,0,4]]},
        "branches": [{"height": 1.5, "azimuth": 90, "elevation": 30, "length": 2,
                      "gamma": 0.4, "death_time": 6, "dieback_exponent": 3}]})");
    ASSERT_EQ(s.chains().size(), 2u);
    const auto& seg = s.segment(s.chain(1).firstSegment);
    Vec3 a = s.start(seg), b = s.end(seg);
    EXPECT_NEAR(a.z, 1.5, 1e-12);
    EXPECT_NEAR(b.x, 0, 1e-12);
    EXPECT_NEAR(b.y, 2 * std::cos(std::numbers::pi / 6), 1e-12);
    EXPECT_NEAR(b.z, 1.5 + 2 * 0.5, 1e-12);
    EXPECT_DOUBLE_EQ(s.node(seg.from).birthTime, 1.5);
    EXPECT_DOUBLE_EQ(s.node(seg.to).birthTime, 3.5);
    EXPECT_EQ(seg.kind, SegmentKind::Branch);
    EXPECT_EQ(seg.order, 1);
    EXPECT_DOUBLE_EQ(seg.gamma, 0.4);
    EXPECT_DOUBLE_EQ(seg.deathTime, 6);
    EXPECT_DOUBLE_EQ(seg.diebackExponent, 3);
}

TEST(SkeletonFile, SubBranchesAttachAlongTheirParent) {
    Skeleton s = parse(R"({"trunk": {"points": [[0,0,0],[0,0,4]]},
        "branches": [{"height": 1, "direction": [1,0,0], "length": 2,
                      "branches": [{"at": 0.5, "direction": [0,1,0], "length": 1}]}]})");
    ASSERT_EQ(s.chains().size(), 3u);
    const auto& sub = s.segment(s.chain(2).firstSegment);
    EXPECT_EQ(sub.order, 2);
    EXPECT_EQ(s.chain(2).parentChain, 1);
    EXPECT_NEAR(s.start(sub).x, 0.5, 1e-12);
    EXPECT_DOUBLE_EQ(s.node(sub.from).birthTime, 1.5);
}

TEST(SkeletonFile, BundledSkeletonsLoad) {
    for (const char* name : {"straight-trunk", "bent-trunk", "conifer", "broadleaf"}) {
        Skeleton s = loadSkeletonFile(std::string(NENRIN_SOURCE_DIR) + "/scenes/skeletons/" + name +
                                      ".json");
        EXPECT_GE(s.segments().size(), 1u) << name;
    }
    Skeleton bent =
        loadSkeletonFile(std::string(NENRIN_SOURCE_DIR) + "/scenes/skeletons/bent-trunk.json");
    EXPECT_GE(bent.trunkSegmentCount(), 3u);
    Skeleton conifer =
        loadSkeletonFile(std::string(NENRIN_SOURCE_DIR) + "/scenes/skeletons/conifer.json");
    EXPECT_GE(conifer.chains().size(), 31u);
    int dead = 0;
    for (uint32_t c = 1; c < conifer.chains().size(); ++c)
        dead += std::isfinite(conifer.segment(conifer.chain(c).firstSegment).deathTime);
    EXPECT_GT(dead, 5);
}

TEST(SkeletonFile, BadInputNamesThePlace) {
    EXPECT_EQ(errorOf(R"({"trunk": {"points": []}})"),
              "s.json: trunk.points: expected at least 2 trunk points, found 0");
    EXPECT_EQ(errorOf(R"({"branches": []})"), "s.json: trunk: missing required trunk");
    EXPECT_EQ(errorOf(R"({"elongation_speed": -2, "trunk": {"points": [[0,0,0],[0,0,1]]}})"),
              "s.json: elongation_speed: expected at least 0.0001 (m/year: 0.1 mm a year, slower "
              "than any tree grows), found -2");
    EXPECT_EQ(errorOf(R"({"trunk": {"points": [[0,0,0],[0,0,1]]},
        "branches": [{"height": 0.5, "direction": [1,0,0]},
                     {"height": 0.5, "direction": [1,0,0], "gamma": 0}]})"),
              "s.json: branches[1].gamma: expected at least 0.001 (of the trunk's radial speed: "
              "a branch thickening a thousandth as fast), found 0");
    EXPECT_NE(errorOf(R"({"trunk": {"points": [[0,0,0],[0,0,1]]},
        "branches": [{"start": [0.5, 0, 0.5], "direction": [1,0,0]}]})")
                  .find("branches[0].start: the branch starts 0.5 m off its parent trunk"),
              std::string::npos);
    EXPECT_NE(errorOf(R"({"trunk": {"points": [[0,0,0],[0,0,1]]},
        "branches": [{"height": 3, "direction": [1,0,0]}]})")
                  .find("branches[0].height: height 3 m is off the trunk"),
              std::string::npos);
    EXPECT_EQ(errorOf(R"({"trunk": {"points": [[0,0,0],[0,0,1]]}, "brnches": []})"),
              "s.json: brnches: unknown key (misspelled? see the format documentation)");
    EXPECT_EQ(errorOf(R"({"trunk": {"points": [[0,0,0],[0,0,1]]},
        "branches": [{"height": 0.5, "points": [[0,0,0.5], [1,0,0.5]]}]})"),
              "s.json: branches[0].points: point 0 coincides with the branch's start on its "
              "parent: expected segments of non-zero length");
    EXPECT_EQ(errorOf(R"({"trunk": {"points": [[0,0,0],[0,0,1]]},
        "branches": [{"height": 0.5, "points": [[1,0,0.5], [1,0,0.5]]}]})"),
              "s.json: branches[0].points: points 0 and 1 coincide: expected segments of "
              "non-zero length");
    EXPECT_EQ(errorOf(R"({"trunk": {"points": [[0,0,0],[0,0,0]]}})"),
              "s.json: trunk.points: points 0 and 1 coincide: expected segments of non-zero "
              "length");
}

}  // namespace
}  // namespace nenrin
