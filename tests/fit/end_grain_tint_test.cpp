#include "fit/end_grain_tint.h"

#include <gtest/gtest.h>

#include <vector>

#include "grain/cielab.h"
#include "grain/grain_params.h"

namespace nenrin {
namespace {

/// Faces A..F of a cube whose fibre runs along y: B and D are end grain.
const std::vector<double> kEndWeights = {0, 1, 0, 1, 0, 0};
constexpr int kSize = 8;

/// A stand-in for baking: every pixel is the grain's early wood colour, times its end-grain
/// tint on the end faces. The photographs: side faces `wood`, end faces `wood` x `endTint`;
/// a quarter of face D stained to `stain` x that (a knot's halo, as on the hinoki cube).
struct TintBakes {
    const nlohmann::json& grain;
    Rgb wood, endTint;
    double stain = 1;

    std::vector<FaceFigures> operator()() const {
        const GrainParams g = parseGrain(grain, "test grain");
        const Rgb baked = g.colour.earlyWood;
        const Rgb tint = g.colour.endGrainTint;
        std::vector<FaceFigures> faces(kEndWeights.size());
        for (size_t i = 0; i < faces.size(); ++i) {
            FaceFigures& f = faces[i];
            const bool end = kEndWeights[i] > 0.5;
            f.name = std::string(1, char('A' + i));
            f.bake.width = f.bake.height = kSize;
            f.bake.data.assign(size_t(kSize * kSize * BakedGrid::kChannels), 0.f);
            for (auto& p : f.photo) p = Plane(kSize, kSize);
            Rgb bakeSum, photoSum;
            for (int y = 0; y < kSize; ++y)
                for (int x = 0; x < kSize; ++x) {
                    const Rgb b = end ? multiply(baked, tint) : baked;
                    Rgb p = end ? multiply(wood, endTint) : wood;
                    if (f.name == "D" && x < kSize / 2 && y < kSize / 2) p = p * stain;
                    float* px = f.bake.at(x, y);
                    px[0] = float(b.r), px[1] = float(b.g), px[2] = float(b.b);
                    f.photo[0].at(x, y) = p.r, f.photo[1].at(x, y) = p.g, f.photo[2].at(x, y) = p.b;
                    bakeSum = bakeSum + b, photoSum = photoSum + p;
                }
            f.dE = deltaE(labFromLinearSrgb(bakeSum * (1.0 / (kSize * kSize))),
                          labFromLinearSrgb(photoSum * (1.0 / (kSize * kSize))));
        }
        return faces;
    }
};

nlohmann::json grainWithColour(const Rgb& wood) {
    return {{"colour",
             {{"early_wood", {wood.r, wood.g, wood.b}},
              {"late_wood", {wood.r * 0.8, wood.g * 0.8, wood.b * 0.8}},
              {"end_grain", {{"tint", {0.87, 0.93, 1.0}}}}}}};
}

TEST(EndGrainTint, TakesTheEndFacesColourAgainstTheSideFacesPastAStain) {
    nlohmann::json grain = grainWithColour({0.5, 0.4, 0.3});
    // The photos: the wood 10 % lighter, its end grain darker and redder than the preset's.
    const TintBakes bake{grain, {0.55, 0.44, 0.33}, {0.8, 0.7, 0.6}, 0.5};
    std::vector<FaceFigures> faces = bake();
    const int bakes = matchEndGrainTint(grain, faces, kEndWeights, bake, 3);
    EXPECT_GE(bakes, 1);
    const ColourParams c = parseGrain(grain, "fitted").colour;
    // The stain (a quarter of one end face) moves the medians nothing.
    EXPECT_NEAR(c.endGrainTint.r, 0.8, 0.01);
    EXPECT_NEAR(c.endGrainTint.g, 0.7, 0.01);
    EXPECT_NEAR(c.endGrainTint.b, 0.6, 0.01);
    EXPECT_NEAR(c.earlyWood.r, 0.55, 0.01);
    for (const FaceFigures& f : faces) {
        if (f.name != "D") {
            EXPECT_LT(f.dE, 0.5) << f.name;
        }
    }
}

TEST(EndGrainTint, AStainAloneChangesNothingAndBothKindsAreNeeded) {
    // The preset's tint is the photographs', but for a quarter of face D stained to a fifth:
    // the medians see no difference, and the grain stays as it was.
    nlohmann::json grain = grainWithColour({0.5, 0.4, 0.3});
    const nlohmann::json before = grain;
    const TintBakes stained{grain, {0.5, 0.4, 0.3}, {0.87, 0.93, 1.0}, 0.2};
    std::vector<FaceFigures> faces = stained();
    EXPECT_EQ(matchEndGrainTint(grain, faces, kEndWeights, stained, 3), 0);
    EXPECT_EQ(grain, before) << "the preset's tint already fits all but D's stain";

    // Side faces only: nothing to compare the end grain with.
    const std::vector<double> allSide(6, 0.0);
    EXPECT_EQ(matchEndGrainTint(grain, faces, allSide, stained, 3), 0);
    EXPECT_EQ(grain, before);
}

}  // namespace
}  // namespace nenrin
