#include "skeleton/skeleton_writer.h"

#include <gtest/gtest.h>

#include "skeleton/skeleton_file.h"
#include "skeleton/synthetic_tree.h"
#include "util/input_error.h"
#include "util/json_reader.h"

namespace nenrin {
namespace {

void expectSameSkeleton(const Skeleton& a, const Skeleton& b) {
    ASSERT_EQ(a.nodes().size(), b.nodes().size());
    ASSERT_EQ(a.segments().size(), b.segments().size());
    ASSERT_EQ(a.chains().size(), b.chains().size());
    for (size_t i = 0; i < a.nodes().size(); ++i) {
        EXPECT_EQ(a.node(i).position, b.node(i).position) << "node " << i;
        EXPECT_EQ(a.node(i).birthTime, b.node(i).birthTime) << "node " << i;
        EXPECT_EQ(a.node(i).radius, b.node(i).radius) << "node " << i;
    }
    for (size_t i = 0; i < a.segments().size(); ++i) {
        const auto &sa = a.segment(i), &sb = b.segment(i);
        EXPECT_EQ(sa.parent, sb.parent) << "segment " << i;
        EXPECT_EQ(sa.chain, sb.chain);
        EXPECT_EQ(sa.order, sb.order);
        EXPECT_EQ(sa.gamma, sb.gamma);
        EXPECT_EQ(sa.deathTime, sb.deathTime);
        EXPECT_EQ(sa.diebackExponent, sb.diebackExponent);
    }
    EXPECT_EQ(a.ringWidths(), b.ringWidths());
}

TEST(SkeletonWriter, RoundTripsARandomTreeExactly) {
    SyntheticTreeOptions o;
    o.seed = 7;
    o.totalSegments = 400;
    Skeleton tree = makeSyntheticTree(o);
    Skeleton back = parseSkeleton(skeletonToJson(tree, {}), "tree.json");
    expectSameSkeleton(tree, back);
}

TEST(SkeletonWriter, RoundTripsRadiiNestedBranchesLateBudsAndRingWidths) {
    Skeleton s;
    s.addTrunk({{0, 0, 0}, {0, 0, 1}, {0.01, 0, 2}}, {0, 1, 2.5}, {0.1, 0.08, 0.05});
    // A branch from a dormant bud: it starts 3 years after the trunk passed its base.
    uint32_t b = s.addBranch(0, {{0, 0, 0.5}, {0.5, 0, 0.7}, {0.9, 0.1, 0.8}}, {3.5, 4, 5},
                             {0.4, 6, 2}, {0.03, 0.02, 0.01});
    s.addBranch(s.chain(b).firstSegment + 1, {{0.5, 0, 0.7}, {0.6, 0.3, 0.8}}, {4, 4.5},
                {0.3, kNeverDies, 1}, {0.01, 0.005});
    s.setRingWidths({0.004, 0.0035, 0.001, 0.006});
    nlohmann::json j = skeletonToJson(s, {"test tree", {{"model", "hand"}}});
    EXPECT_EQ(j["source"]["model"], "hand");
    Skeleton back = parseSkeleton(j, "tree.json");
    expectSameSkeleton(s, back);
}

TEST(SkeletonWriter, RejectsBirthTimesThatGoBackwards) {
    auto load = [](const std::string& text) {
        return parseSkeleton(parseJsonText(text, "t.json"), "t.json");
    };
    EXPECT_THROW(load(R"({"trunk": {"points": [[0,0,0],[0,0,1]], "birth_times": [2, 1]}})"),
                 InputError);
    EXPECT_THROW(load(R"({"trunk": {"points": [[0,0,0],[0,0,1]], "birth_times": [0]}})"),
                 InputError);
    EXPECT_THROW(load(R"({"trunk": {"points": [[0,0,0],[0,0,1]], "radii": [0.1, -1]}})"),
                 InputError);
    EXPECT_THROW(load(R"({"trunk": {"points": [[0,0,0],[0,0,4]], "birth_times": [0, 4]},
        "branches": [{"height": 2, "start_birth_time": 1, "points": [[1,0,2]]}]})"),
                 InputError);
    // A 0 is a locally absent ring (it merges with the next); negative, huge or all-zero
    // widths are not rings.
    EXPECT_NO_THROW(load(R"({"trunk": {"points": [[0,0,0],[0,0,1]]}, "ring_widths": [0.1, 0]})"));
    EXPECT_THROW(load(R"({"trunk": {"points": [[0,0,0],[0,0,1]]}, "ring_widths": [0.1, -0.001]})"),
                 InputError);
    EXPECT_THROW(load(R"({"trunk": {"points": [[0,0,0],[0,0,1]]}, "ring_widths": [0.1, 1e308]})"),
                 InputError);
    EXPECT_THROW(load(R"({"trunk": {"points": [[0,0,0],[0,0,1]]}, "ring_widths": [0, 0]})"),
                 InputError);
    EXPECT_THROW(load(R"({"trunk": {"points": [[0,0,0],[0,0,1]]}, "ring_widths": [0.001],
        "ring_series": {"file": "x.rwl", "series": "A"}})"),
                 InputError);
    try {
        load(R"({"trunk": {"points": [[0,0,0],[0,0,4]]},
            "branches": [{"height": 2, "points": [[1,0,2]], "birth_times": [1]}]})");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("branches[0].birth_times"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace nenrin
