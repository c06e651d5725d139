// Saw marks (finish "sawn"): parallel striations on a cut face, strongest on end grain, none
// with any other finish, fading as the footprint spans many of them.

#include "shader/saw_marks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "shader/finish.h"

namespace nenrin {
namespace {

Finish sawn() {
    Finish f;
    EXPECT_TRUE(finishPreset("sawn", f));
    return f;
}

/// Brightness over a 4 mm square of the plane z = 1 (an end-grain face of a trunk along z).
std::vector<double> patch(const Finish& f, double endGrain, const Vec3& dpdx = {},
                          const Vec3& dpdy = {}, int n = 100) {
    std::vector<double> v;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            v.push_back(sawMarks(f, {0.07 + 0.00004 * i, 0.00004 * j, 1.0}, dpdx, dpdy, endGrain)
                            .brightness);
    return v;
}

double rms(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x * x;
    return std::sqrt(s / double(v.size()));
}

TEST(SawMarks, OnlyTheSawnFinishHasThem) {
    for (const char* name : {"oiled", "matte", "varnished", "bare", "brushed"}) {
        Finish f;
        ASSERT_TRUE(finishPreset(name, f));
        EXPECT_EQ(rms(patch(f, 1)), 0) << name;
    }
    EXPECT_GT(rms(patch(sawn(), 1)), 0.05);
}

TEST(SawMarks, AreParallelStriations) {
    // The structure tensor of the brightness over the patch: marks are lines, so its
    // gradients all point one way (an eigenvalue ratio far above the ~1 of round features).
    const int n = 100;
    const std::vector<double> v = patch(sawn(), 1, {}, {}, n);
    double xx = 0, yy = 0, xy = 0;
    for (int i = 0; i + 1 < n; ++i)
        for (int j = 0; j + 1 < n; ++j) {
            const double gx = v[(i + 1) * n + j] - v[i * n + j];
            const double gy = v[i * n + j + 1] - v[i * n + j];
            xx += gx * gx, yy += gy * gy, xy += gx * gy;
        }
    const double tr = xx + yy, d = std::sqrt((xx - yy) * (xx - yy) + 4 * xy * xy);
    EXPECT_GT((tr + d) / (tr - d), 20);
}

TEST(SawMarks, SideGrainShowsAFifthOfEndGrain) {
    const std::vector<double> end = patch(sawn(), 1), side = patch(sawn(), 0);
    for (size_t k = 0; k < end.size(); ++k) EXPECT_NEAR(side[k], 0.2 * end[k], 1e-12);
}

TEST(SawMarks, FadeAsTheFootprintSpansManyMarks) {
    const Finish f = sawn();
    const double sharp = rms(patch(f, 1));
    // A footprint 16 spacings across (along every axis): a quarter of the contrast.
    const Vec3 wide = Vec3{1, 1, 1} * (16 * f.sawMarkSpacing);
    EXPECT_NEAR(rms(patch(f, 1, wide, wide)) / sharp, 0.25, 0.1);
    // Past 64 marks: nothing (it would only be noise).
    const Vec3 huge = Vec3{1, 1, 1} * (200 * f.sawMarkSpacing);
    EXPECT_EQ(rms(patch(f, 1, huge, huge)), 0);
}

}  // namespace
}  // namespace nenrin
