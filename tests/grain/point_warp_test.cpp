// The grain's measured displacement lattice (grain/point_warp.h, the "warp" key): trilinear
// inside, fading to zero over one cell outside, read strictly.

#include "grain/point_warp.h"

#include <gtest/gtest.h>

#include "grain/grain_params.h"
#include "util/input_error.h"

namespace nenrin {
namespace {

WarpParams twoByTwo() {
    WarpParams w;
    w.origin = {0, 0, 0};
    w.step = {0.01, 0.01, 0.01};
    w.nx = w.ny = w.nz = 2;
    for (int k = 0; k < 2; ++k)
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) w.displacement.push_back({0.001 * i, 0.002 * j, 0.0});
    return w;
}

TEST(PointWarp, InterpolatesInsideAndFadesOutside) {
    const WarpParams w = twoByTwo();
    // Linear in x and y inside: the nodes' values and the midpoints'.
    EXPECT_NEAR(pointWarp({0.01, 0.01, 0.005}, w).x, 0.001, 1e-15);
    EXPECT_NEAR(pointWarp({0.005, 0.0025, 0.005}, w).x, 0.0005, 1e-15);
    EXPECT_NEAR(pointWarp({0.005, 0.0025, 0.005}, w).y, 0.0005, 1e-15);
    // Half a cell past the edge: half of the edge's value; a cell past: nothing.
    EXPECT_NEAR(pointWarp({0.015, 0.01, 0.005}, w).x, 0.0005, 1e-15);
    EXPECT_EQ(pointWarp({0.02, 0.01, 0.005}, w).x, 0.0);
    EXPECT_EQ(pointWarp({1e9, -1e9, 0}, w).y, 0.0);
    EXPECT_EQ(pointWarp({0.005, 0.005, 0.005}, WarpParams{}).x, 0.0);  // off
}

TEST(PointWarp, GrainFilesReadAndWriteIt) {
    GrainParams g;
    g.warp = twoByTwo();
    const GrainParams back = parseGrain(grainToJson(g), "g.json");
    ASSERT_EQ(back.warp.displacement.size(), 8u);
    EXPECT_EQ(back.warp.displacement[7].y, 0.002);
    EXPECT_EQ(back.warp.nx, 2);

    auto expectError = [](nlohmann::json warp, const std::string& where) {
        try {
            parseGrain({{"warp", warp}}, "g.json");
            ADD_FAILURE() << "accepted " << warp.dump();
        } catch (const InputError& e) {
            EXPECT_EQ(e.where(), where) << e.what();
        }
    };
    const nlohmann::json good = grainToJson(g)["warp"];
    nlohmann::json w = good;
    w["size"] = {2, 2, 3};
    expectError(w, "warp.displacement");  // 8 vectors for 12 nodes
    w = good;
    w["size"] = {1, 2, 2};
    expectError(w, "warp.size");
    w = good;
    w["step"] = {0.01, 0, 0.01};
    expectError(w, "warp.step");
    w = good;
    w["displacement"][3] = {0.1, 0, 0};
    expectError(w, "warp.displacement");
    w = good;
    w["seed"] = 1;
    expectError(w, "warp.seed");
}

}  // namespace
}  // namespace nenrin
