#include "fit/profile_sharpening.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace nenrin {
namespace {

/// Hinoki's kind of ring (docs/species.md): the early wood darkening slowly across the ring
/// (E up to 0.6), then a thin late-wood line (the last 7 %), E at 33 phases as the fit reads it.
std::vector<double> ringWithALine() {
    std::vector<double> e(33);
    for (size_t j = 0; j < e.size(); ++j) {
        const double u = double(j) / 32;
        e[j] = u > 0.93 ? 1.0 : 0.6 * u / 0.93;
    }
    return e;
}

double meanAbsoluteDifference(const std::vector<double>& a, const std::vector<double>& b) {
    double sum = 0;
    for (size_t i = 0; i < a.size(); ++i) sum += std::abs(a[i] - b[i]);
    return sum / double(a.size());
}

TEST(ProfileSharpening, MeasuresTheBlurOfTheRingBoundaryAndRestoresTheLine) {
    const std::vector<double> truth = ringWithALine();
    for (double blur : {0.03, 0.045}) {
        const std::vector<double> measured = blurLateWoodProfile(truth, blur);
        const SharpenedProfile sharpened = sharpenLateWoodProfile(measured);
        // The fall after a line a few samples wide is narrower than a step's would be: the
        // estimate errs low (~0.7-0.8 of the blur here), leaving blur rather than inventing
        // sharpness.
        EXPECT_GT(sharpened.blur, 0.6 * blur) << "blur " << blur;
        EXPECT_LT(sharpened.blur, 1.05 * blur) << "blur " << blur;
        // The line comes back (the blur took its peak down to 0.8-0.9) and the profile as a
        // whole is nearer the truth.
        EXPECT_GT(*std::max_element(sharpened.profile.begin(), sharpened.profile.end()), 0.9);
        EXPECT_LT(*std::max_element(measured.begin(), measured.end()), 0.93);
        EXPECT_LT(meanAbsoluteDifference(sharpened.profile, truth),
                  0.75 * meanAbsoluteDifference(measured, truth))
            << "blur " << blur;
        for (double e : sharpened.profile) {
            EXPECT_GE(e, 0);
            EXPECT_LE(e, 1);
        }
    }
}

TEST(ProfileSharpening, LeavesASharpOrAFlatProfileAsItIs) {
    const std::vector<double> sharp = ringWithALine();
    const SharpenedProfile fromSharp = sharpenLateWoodProfile(sharp);
    EXPECT_EQ(fromSharp.blur, 0);
    EXPECT_EQ(fromSharp.profile, sharp);
    const std::vector<double> flat(33, 0.4);  // no rings to speak of
    EXPECT_EQ(sharpenLateWoodProfile(flat).profile, flat);
    EXPECT_EQ(sharpenLateWoodProfile(flat).blur, 0);
}

}  // namespace
}  // namespace nenrin
