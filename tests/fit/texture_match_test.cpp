#include "fit/texture_match.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "grain/grain_params.h"

namespace nenrin {
namespace {

/// Faces A..F of a cube whose fibre runs along y: B and D are end grain.
const std::vector<double> kEndWeights = {0, 1, 0, 1, 0, 0};

/// A stand-in for baking: each face's fine texture is part the anatomy's cells (their summed
/// amplitude, times 1 + the end-grain texture on end faces) and part what the anatomy does not
/// make (ring edges, a constant); the end faces' mid texture grows with their pores' contrast
/// (1 + the end-grain contrast). `photoFine` and `photoMid` are what the photographs measure.
struct ModelBakes {
    const nlohmann::json& grain;
    double photoFine, photoEndFine, photoEndMid;
    int bakes = 0;

    std::vector<FaceFigures> operator()() {
        ++bakes;
        const GrainParams g = parseGrain(grain, "test grain");
        const double cells = g.anatomy.fibreAmplitude + g.anatomy.speckleAmplitude;
        std::vector<FaceFigures> faces(kEndWeights.size());
        for (size_t i = 0; i < faces.size(); ++i) {
            const bool end = kEndWeights[i] > 0.5;
            const double c = cells * (end ? 1 + g.colour.endGrainTexture : 1);
            const double fine = std::hypot(0.1, c);
            faces[i].name = std::string(1, char('A' + i));
            faces[i].fineRatio = fine / (end ? photoEndFine : photoFine);
            faces[i].midRatio =
                end ? (1 + g.colour.endGrainContrast) * g.anatomy.poreDarkening / photoEndMid : 1;
        }
        return faces;
    }
};

nlohmann::json grainWith(bool pores) {
    nlohmann::json g = {{"anatomy",
                         {{"fibres", {{"amplitude", 0.05}}},
                          {"speckle", {{"amplitude", 0.15}}},
                          {"streaks", {{"amplitude", 0.08}}}}},
                        {"colour", {{"end_grain", {{"texture", 0.2}, {"contrast", -0.3}}}}}};
    if (pores) g["anatomy"]["pores"] = {{"kind", "ring-porous"}, {"darkening", 0.5}};
    return g;
}

TEST(TextureMatch, BringsSideAndEndFacesToThePhotographsFineAndMidTexture) {
    nlohmann::json grain = grainWith(true);
    // The photos: side cells 1.3 x the base's, end grain 1.6 x the side's, end mid as pores
    // darkening 0.6 (the base's 0.5 x 0.7 = 0.35).
    ModelBakes bake{grain, std::hypot(0.1, 0.26), std::hypot(0.1, 0.26 * 1.6), 0.6};
    std::vector<FaceFigures> faces = bake();
    bake.bakes = 0;
    const TextureStrengths s = matchTexture(grain, faces, kEndWeights, std::ref(bake));
    for (const FaceFigures& f : faces) {
        EXPECT_NEAR(f.fineRatio, 1, 0.05) << f.name;
        EXPECT_NEAR(f.midRatio, 1, 0.05) << f.name;
    }
    EXPECT_NEAR(s.sideCells, 1.3, 0.1);
    EXPECT_EQ(s.bakes, bake.bakes);
    EXPECT_LE(s.bakes, kTextureRounds);
    const GrainParams g = parseGrain(grain, "fitted");
    EXPECT_NEAR(g.anatomy.fibreAmplitude / g.anatomy.speckleAmplitude, 1.0 / 3, 0.01)
        << "the cells keep their mix";
    EXPECT_DOUBLE_EQ(g.anatomy.streakAmplitude, 0.08) << "side faces' rest is not fitted";
    EXPECT_DOUBLE_EQ(g.anatomy.poreDarkening, 0.5);
}

TEST(TextureMatch, StaysWithinItsBoundsAndLeavesEndContrastWithoutPores) {
    // Photographs with 5 x the texture: the side cells stop at twice the base's; without
    // pores the end grain's contrast (streaks cut across) is left as it was.
    nlohmann::json grain = grainWith(false);
    ModelBakes bake{grain, std::hypot(0.1, 1.0), std::hypot(0.1, 1.2), 0.1};
    std::vector<FaceFigures> faces = bake();
    const TextureStrengths s = matchTexture(grain, faces, kEndWeights, std::ref(bake));
    EXPECT_DOUBLE_EQ(s.sideCells, 2.0);
    EXPECT_LE(s.endCells, 2.0 + 1e-9);
    const GrainParams g = parseGrain(grain, "fitted");
    EXPECT_NEAR(g.anatomy.fibreAmplitude + g.anatomy.speckleAmplitude, 0.4, 1e-4);
    EXPECT_LE(
        (g.anatomy.fibreAmplitude + g.anatomy.speckleAmplitude) * (1 + g.colour.endGrainTexture),
        0.8 + 1e-3)
        << "the end grain's cells stay within the filter's bound";
    EXPECT_DOUBLE_EQ(g.colour.endGrainContrast, -0.3);
    EXPECT_EQ(s.endRest, 1.0);
}

TEST(TextureMatch, LeavesMatchedTextureAndGrainsWithoutAnatomyAlone) {
    nlohmann::json grain = grainWith(true);
    const nlohmann::json before = grain;
    ModelBakes bake{grain, std::hypot(0.1, 0.2), std::hypot(0.1, 0.24), 0.35};
    std::vector<FaceFigures> faces = bake();
    bake.bakes = 0;
    EXPECT_EQ(matchTexture(grain, faces, kEndWeights, std::ref(bake)).bakes, 0);
    EXPECT_EQ(bake.bakes, 0);

    nlohmann::json bare = nlohmann::json::object();
    ModelBakes bareBake{bare, 1, 1, 1};
    std::vector<FaceFigures> bareFaces(6);
    EXPECT_EQ(matchTexture(bare, bareFaces, kEndWeights, std::ref(bareBake)).bakes, 0);
    EXPECT_EQ(bare, nlohmann::json::object());
}

}  // namespace
}  // namespace nenrin
