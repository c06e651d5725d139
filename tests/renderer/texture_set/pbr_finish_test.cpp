// The mapping of nenrin's finishes onto the PBR model of other tools.

#include "renderer/texture_set/pbr_finish.h"

#include <gtest/gtest.h>

#include <cmath>

namespace nenrin {
namespace {

TEST(PbrFinish, RoughnessIsPerceptual) {
    for (double alpha : {0.0, 0.01, 0.12, 0.55, 1.0})
        EXPECT_NEAR(std::pow(perceptualRoughness(alpha), 2), alpha, 1e-12);
    EXPECT_EQ(perceptualRoughness(-1), 0);
    EXPECT_EQ(perceptualRoughness(4), 1);
}

TEST(PbrFinish, OiledIsACoatOverAnAnisotropicFibreLobe) {
    Finish oiled;
    ASSERT_TRUE(finishPreset("oiled", oiled));
    PbrFinish p = pbrFinish(oiled);
    EXPECT_EQ(p.coatWeight, 1);
    EXPECT_NEAR(p.coatRoughness * p.coatRoughness, oiled.coatRoughness, 1e-12);  // alpha 0.12
    EXPECT_NEAR(p.baseRoughness * p.baseRoughness, oiled.fibreWidth, 1e-12);
    EXPECT_GT(p.anisotropy, 0.5);
    EXPECT_EQ(p.ior, 1.5);
}

TEST(PbrFinish, BareWoodHasNoCoatAndARoundLobe) {
    Finish bare;
    ASSERT_TRUE(finishPreset("bare", bare));
    PbrFinish p = pbrFinish(bare);
    EXPECT_EQ(p.coatWeight, 0);
    EXPECT_EQ(p.anisotropy, 0);
    EXPECT_NEAR(p.baseRoughness * p.baseRoughness, bare.woodRoughness, 1e-12);
}

TEST(PbrFinish, VarnishIsSharperThanOil) {
    Finish oiled, varnished;
    ASSERT_TRUE(finishPreset("oiled", oiled));
    ASSERT_TRUE(finishPreset("varnished", varnished));
    EXPECT_LT(pbrFinish(varnished).coatRoughness, pbrFinish(oiled).coatRoughness);
}

}  // namespace
}  // namespace nenrin
