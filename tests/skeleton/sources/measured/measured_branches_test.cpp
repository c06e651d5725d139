// Hayashi & Takahashi's measured-branch format: offsets by the paper's formula summed from the
// ground, the hierarchy from the B-numbers, birth times from the elongation speed, and strict
// errors that name the file and the JSON path.
#include "skeleton/sources/measured/measured_branches.h"

#include <gtest/gtest.h>

#include <cmath>

#include "skeleton/skeleton_file.h"
#include "skeleton/skeleton_writer.h"
#include "util/input_error.h"
#include "util/json_reader.h"

namespace nenrin {
namespace {

MeasuredTree parse(const std::string& text) {
    return parseMeasuredTree(parseJsonText(text, "tree.json"), "tree.json");
}

std::string errorOf(const std::string& text) {
    try {
        parse(text);
    } catch (const InputError& e) {
        return e.what();
    }
    return "accepted";
}

void expectNear(const Vec3& a, const Vec3& b, double tol = 1e-12) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

// By hand: trunk internode 1 straight up 1 m; internode 2 l = 0.5 m, theta = 90 (east, +X),
// phi = 60: x = 0.5 sin90 cos60 = 0.25, y = 0.5 cos90 cos60 = 0, z = 0.5 sin60 = 0.4330127.
// B100 leaves node 1 (z = 1) towards theta = 180 (south, -Y), level: tip (0, -0.4, 1).
// B110 leaves B100's node 1 (its tip) east, rising 30 deg: + (0.2 cos30, 0, 0.2 sin30).
// Sa = 0.5 m/year: B110's tip is 1 + 0.4 + 0.2 = 1.6 m of growth from the ground = 3.2 years.
constexpr const char* kHandExample = R"({
  "unit": "cm", "elongation_speed": 0.5,
  "trunk": [[100, 0, 90, 30], [50, 90, 60, 20]],
  "branches": {
    "B100": {"node": 1, "internodes": [[40, 180, 0, 8]]},
    "B110": {"node": 1, "internodes": [[20, 90, 30, 2]], "gamma": 0.3}
  }
})";

TEST(MeasuredBranches, OffsetsAndTimesMatchAHandComputedExample) {
    MeasuredTree t = parse(kHandExample);
    const Skeleton& sk = t.skeleton;
    ASSERT_EQ(sk.chains().size(), 3u);
    EXPECT_EQ(t.elongationSpeed, 0.5);
    expectNear(sk.node(0).position, {0, 0, 0});
    expectNear(sk.node(1).position, {0, 0, 1});
    expectNear(sk.node(2).position, {0.25, 0, 1 + 0.5 * std::sqrt(3.0) / 2});
    EXPECT_NEAR(sk.node(2).birthTime, 3.0, 1e-12);  // 1.5 m / 0.5 m/year

    const auto& b100 = sk.chain(t.chainOfBranch.at("B100"));
    EXPECT_EQ(b100.order, 1);
    EXPECT_EQ(b100.parentChain, 0);
    const auto& s100 = sk.segment(b100.firstSegment);
    EXPECT_EQ(s100.parent, 0);  // the trunk segment ending at node 1
    expectNear(sk.start(s100), {0, 0, 1});
    expectNear(sk.end(s100), {0, -0.4, 1});
    EXPECT_NEAR(sk.node(s100.from).birthTime, 2.0, 1e-12);
    EXPECT_NEAR(sk.node(s100.from).radius, 0.04, 1e-12);  // d = 8 cm

    const auto& b110 = sk.chain(t.chainOfBranch.at("B110"));
    EXPECT_EQ(b110.order, 2);
    EXPECT_EQ(b110.parentChain, static_cast<int32_t>(t.chainOfBranch.at("B100")));
    const auto& s110 = sk.segment(b110.firstSegment);
    expectNear(sk.end(s110), {0.2 * std::sqrt(3.0) / 2, -0.4, 1.1});
    EXPECT_NEAR(sk.node(s110.to).birthTime, 3.2, 1e-12);
    EXPECT_EQ(s110.gamma, 0.3);
    // The newest tip sets the age; B100's gamma comes from the diameters:
    // (0.04 m / (3.2 - 2.0) years) / (0.15 m / 3.2 years).
    EXPECT_NEAR(t.age, 3.2, 1e-12);
    EXPECT_NEAR(s100.gamma, (0.04 / 1.2) / (0.15 / 3.2), 1e-12);

    // The skeleton file written for it loads back to the same geometry and times.
    Skeleton back = parseSkeleton(skeletonToJson(sk, {}), "tree.json");
    ASSERT_EQ(back.nodes().size(), sk.nodes().size());
    for (size_t i = 0; i < sk.nodes().size(); ++i) {
        EXPECT_EQ(back.node(i).position, sk.node(i).position);
        EXPECT_EQ(back.node(i).birthTime, sk.node(i).birthTime);
    }
}

TEST(MeasuredBranches, AgeSetsTheElongationSpeedAndBudDelaysAndDeaths) {
    MeasuredTree t = parse(R"({"age": 8, "trunk": [[2, 0, 90, 0.2], [2, 0, 90, 0.1]],
        "branches": {"B10": {"node": 1, "internodes": [[0.25, 45, 0, 0.05]], "start_time": 5,
                             "death_time": 6},
                     "B11": {"node": 1, "internodes": [[0.2, 90, 10, 0.02]]}}})");
    // The farthest tip (ignoring bud delays) is the trunk's at 4 m: Sa = 4 m / 8 years, so
    // the trunk passed node 1 (2 m) at 4 years and the bud broke a year later.
    EXPECT_EQ(t.elongationSpeed, 0.5);
    const Skeleton& sk = t.skeleton;
    EXPECT_EQ(sk.node(1).birthTime, 4.0);
    const auto& b = sk.segment(sk.chain(t.chainOfBranch.at("B10")).firstSegment);
    EXPECT_EQ(sk.node(b.from).birthTime, 5.0);
    EXPECT_EQ(sk.node(b.to).birthTime, 5.5);
    EXPECT_EQ(b.deathTime, 6.0);
    // A branch dies with its parent.
    const auto& c = sk.segment(sk.chain(t.chainOfBranch.at("B11")).firstSegment);
    EXPECT_EQ(sk.node(c.from).birthTime, 5.5);
    EXPECT_EQ(c.deathTime, 6.0);
    EXPECT_EQ(errorOf(R"({"age": 8, "trunk": [[2, 0, 90, 0.2], [2, 0, 90, 0.1]],
        "branches": {"B10": {"node": 1, "internodes": [[1, 45, 0, 0.05]], "start_time": 3}}})"),
              "tree.json: branches.B10.start_time: the branch starts at 3 years, before its "
              "parent reached node 1 (4 years)");
}

TEST(MeasuredBranches, TheShippedCherryLoads) {
    MeasuredTree t =
        loadMeasuredTree(std::string(NENRIN_SOURCE_DIR) + "/scenes/trees/measured-cherry.json");
    EXPECT_EQ(t.chainOfBranch.size(), 12u);  // trunk + 11 branches
    EXPECT_EQ(t.age, 30);
    const Skeleton& sk = t.skeleton;
    int orders[4] = {0, 0, 0, 0};
    for (const auto& c : sk.chains()) orders[c.order] += 1;
    EXPECT_EQ(orders[1], 6);
    EXPECT_EQ(orders[2], 4);
    EXPECT_EQ(orders[3], 1);
    for (const auto& s : sk.segments()) {
        EXPECT_GT(s.gamma, 0.05);
        EXPECT_LE(s.gamma, 2.0);
        EXPECT_GE(sk.node(s.to).birthTime, sk.node(s.from).birthTime);
        EXPECT_LE(sk.node(s.to).birthTime, 30 + 1e-9);
    }
    EXPECT_EQ(sk.segment(sk.chain(t.chainOfBranch.at("B200")).firstSegment).deathTime, 18);
    EXPECT_NO_THROW(parseSkeleton(skeletonToJson(sk, {}), "cherry.json"));
}

TEST(MeasuredBranches, RejectsBadFilesWithPathBearingMessages) {
    auto tree = [](const std::string& branches, const std::string& trunk = "[[1, 0, 90, 0.2]]") {
        return R"({"elongation_speed": 1, "trunk": )" + trunk + R"(, "branches": {)" + branches +
               "}}";
    };
    EXPECT_EQ(errorOf(tree(R"("B102": {"node": 1, "internodes": [[1, 0, 0, 0.1]]})")),
              "tree.json: branches.B102: bad branch number \"B102\": a non-zero digit after a 0 "
              "(expected B and digits, the non-zero ones first: B100, B120, B121)");
    EXPECT_EQ(errorOf(tree(R"("X100": {"node": 1, "internodes": [[1, 0, 0, 0.1]]})")),
              "tree.json: branches.X100: bad branch number \"X100\": it must start with B "
              "(expected B and digits, the non-zero ones first: B100, B120, B121)");
    EXPECT_EQ(errorOf(tree(R"("B120": {"node": 1, "internodes": [[1, 0, 0, 0.1]]})")),
              "tree.json: branches.B120: parent branch B100 is missing (a branch B120 hangs on "
              "the branch with its last non-zero digit set to 0)");
    EXPECT_EQ(errorOf(tree(R"("B100": {"node": 1, "internodes": [[-1, 0, 0, 0.1]]})")),
              "tree.json: branches.B100.internodes[0][0]: internode length l must be in [1e-6, "
              "100] m, found -1 (the file's unit is 1 m)");
    // Found by fuzzing: an internode of 8e96 m once made a NaN growth time.
    EXPECT_EQ(errorOf(tree(R"("B100": {"node": 1, "internodes": [[8e96, 0, 0, 0.1]]})")),
              "tree.json: branches.B100.internodes[0][0]: internode length l must be in [1e-6, "
              "100] m, found 8e+96 (the file's unit is 1 m)");
    EXPECT_EQ(errorOf(tree(R"("B100": {"node": 1, "internodes": [[1, 1e9, 0, 0.1]]})")),
              "tree.json: branches.B100.internodes[0][1]: azimuth theta must be in [-3600, 3600] "
              "degrees, found 1e+09");
    EXPECT_EQ(errorOf(tree(R"("B100": {"node": 1, "internodes": [[1, 0, 0, 30]]})")),
              "tree.json: branches.B100.internodes[0][3]: base diameter d must be in (0, 20] m, "
              "found 30 (the file's unit is 1 m)");
    EXPECT_EQ(errorOf(tree(R"("B100": {"node": 2, "internodes": [[1, 0, 0, 0.1]]})")),
              "tree.json: branches.B100.node: node 2 is past the tip of the trunk (1 internodes: "
              "nodes 0..1)");
    EXPECT_EQ(errorOf(tree(R"("B100": {"node": 1, "internodes": [[1, 0, 0]]})")),
              "tree.json: branches.B100.internodes[0]: expected an internode [l, theta, phi, d] "
              "(length, azimuth deg, elevation deg, base diameter), found 3 elements");
    EXPECT_EQ(errorOf(tree(R"("B100": {"node": 1, "internodes": [[1, 0, 95, 0.1]]})")),
              "tree.json: branches.B100.internodes[0][2]: elevation phi must be in [-90, 90] "
              "degrees, found 95");
    EXPECT_EQ(errorOf(tree(R"("B100": {"node": 1, "internodes": [[1, 0, 0, 0.1]], "gama": 1})")),
              "tree.json: branches.B100.gama: unknown key (misspelled? see the format "
              "documentation)");
    EXPECT_EQ(errorOf(tree(R"("B100": {"node": 1, "internodes": [[1, 0, 0, 0.1]]},
                               "B1000": {"node": 1, "internodes": [[1, 0, 0, 0.1]]})")),
              "tree.json: branches.B1000: branch numbers must all have the same number of digits "
              "(\"B100\" has 3, \"B1000\" has 4)");
    EXPECT_EQ(errorOf(tree(R"("B100": {"internodes": [[1, 0, 0, 0.1]]})")),
              "tree.json: branches.B100.node: missing: the parent's node the branch leaves from");
    EXPECT_EQ(errorOf(tree("", "[]")),
              "tree.json: trunk: expected a non-empty array of internodes [l, theta, phi, d], "
              "found an empty array");
    EXPECT_EQ(errorOf(R"({"trunk": [[1, 0, 90, 0.2]]})"),
              "tree.json: (top level): give exactly one of \"age\" (years at measurement) and "
              "\"elongation_speed\" (m/year): they define the birth times");
    EXPECT_EQ(errorOf(R"({"age": 1, "trunk": [[1, 0, 90, 0.2]],
        "branches": {"B100": {"node": 0, "internodes": [[1, 0, 0, 0.1]], "start_time": 0.5}}})"),
              "tree.json: age: a branch tip would be born at 1.5 years, after the tree's age 1 "
              "(check start_time)");
    EXPECT_EQ(errorOf(R"({"elongation_speed": 1, "trunk": [[1, 0, 90, 0.2]], "branches": {
        "B10": {"node": 1, "internodes": [[1, 0, 0, 0.1]], "death_time": 1.5},
        "B11": {"node": 1, "internodes": [[1, 0, 0, 0.1]]}}})"),
              "tree.json: branches.B11: its parent B10 is dead at 1.5 years, before the branch "
              "starts (2 years)");
    EXPECT_EQ(errorOf(tree(R"("B100": {"node": 1, "internodes": [[1, 0, 0, 0.1]],
                               "death_time": 0.5})")),
              "tree.json: branches.B100.death_time: the branch dies at 0.5 years, before it "
              "starts (1 years)");
    EXPECT_THROW(loadMeasuredBranches("/nonexistent/tree.json"), InputError);
}

}  // namespace
}  // namespace nenrin
