// Akagi & Kitajima's hierarchical model: the MCMC recovers known weights from data drawn from
// the model itself; the shipped species fit and give plausible trees of their form.
#include "skeleton/sources/akagi/akagi_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "skeleton/skeleton_file.h"
#include "tests/scratch_path.h"
#include "util/input_error.h"
#include "util/random_draws.h"

namespace nenrin {
namespace {

// Synthetic observations from the model: Height ~ Gamma(exp(W0 + W1 Radius + ID + Err), beta)
// and MainAngle ~ Normal(T0 + T1 MainGrowth + ID, sigma); 40 trees x 4 rows.
struct Truth {
    double w0 = 2.0, w1 = 8.0, beta = 1.5, sigmaIdGamma = 0.15, sigmaErr = 0.05;
    double t0 = 4.0, t1 = 12.0, sigma = 1.5, sigmaIdNormal = 1.0;
};

ObservationTable syntheticTable(const Truth& truth, uint64_t seed) {
    SplitMix rng(seed);
    ObservationTable t;
    t.source = "synthetic";
    for (int tree = 0; tree < 40; ++tree) {
        std::string id = "T";  // (not "T" + to_string: GCC 12 warns falsely on that)
        id += std::to_string(tree);
        t.treeIds.push_back(id);
        double radius = rng.uniform(0.1, 0.4);
        double idGamma = drawNormal(rng, 0, truth.sigmaIdGamma);
        double idNormal = drawNormal(rng, 0, truth.sigmaIdNormal);
        for (int r = 0; r < 4; ++r) {
            AkagiParams p;
            p.radius = radius;
            double shape = std::exp(truth.w0 + truth.w1 * radius + idGamma +
                                    drawNormal(rng, 0, truth.sigmaErr));
            p.height = drawGamma(rng, shape, 1 / truth.beta);
            p.mainGrowth = rng.uniform(0.3, 0.8);
            p.mainAngle =
                drawNormal(rng, truth.t0 + truth.t1 * p.mainGrowth + idNormal, truth.sigma);
            // The other columns: independent spread so the fit has something to do.
            p.leafNum = 3 + r, p.leafSize = rng.uniform(0.05, 0.1);
            p.subGrowth = rng.uniform(0.1, 0.2), p.subAngle = rng.uniform(40, 50);
            p.branchPoint = rng.uniform(0.2, 0.4), p.growthGain = rng.uniform(0.2, 0.6);
            t.rows.push_back(p);
            t.rowTree.push_back(tree);
            t.rowLine.push_back(static_cast<int>(t.rows.size()));
        }
    }
    return t;
}

TEST(AkagiModel, McmcRecoversKnownWeightsShapeAndRate) {
    Truth truth;
    McmcOptions o;
    o.burnIn = 2000, o.samples = 800;
    AkagiFit fit = fitAkagiModel(syntheticTable(truth, 17), o);
    const AkagiParamFit& h = fit.params[0];
    ASSERT_EQ(h.covariates, std::vector<int>{1});
    // Tolerance: 3 posterior sd.
    EXPECT_NEAR(h.weightMean[0], truth.w0, 3 * h.weightSd[0]);
    EXPECT_NEAR(h.weightMean[1], truth.w1, 3 * h.weightSd[1]);
    EXPECT_NEAR(h.rateMean, truth.beta, 3 * h.rateSd);
    EXPECT_LT(h.weightSd[1], 0.5 * truth.w1);  // and the data did inform it
    const AkagiParamFit& a = fit.params[6];
    ASSERT_EQ(a.covariates, std::vector<int>{5});
    EXPECT_NEAR(a.weightMean[0], truth.t0, 3 * a.weightSd[0]);
    EXPECT_NEAR(a.weightMean[1], truth.t1, 3 * a.weightSd[1]);
    EXPECT_NEAR(a.sigmaMean, truth.sigma, 3 * a.sigmaSd);
    EXPECT_NEAR(a.sigmaIdMean, truth.sigmaIdNormal, 0.5 * truth.sigmaIdNormal);
    for (const AkagiParamFit& f : fit.params) {
        if (f.constant) continue;  // columns without spread are not sampled
        EXPECT_GT(f.acceptance, 0.2);
        EXPECT_LT(f.acceptance, 0.7);
    }
}

TEST(AkagiModel, PaperCovariatesPutEveryOtherBranchingParameterInEachRegression) {
    McmcOptions o;
    o.burnIn = 300, o.samples = 100, o.paperCovariates = true;
    AkagiFit fit = fitAkagiModel(akagiSpeciesTable("akaezomatsu"), o);
    // P1..P10 except itself, minus BranchNum (constant in this table, so dropped).
    EXPECT_EQ(fit.params[0].covariates, (std::vector<int>{1, 2, 3, 5, 6, 7, 8, 9}));
    EXPECT_EQ(fit.params[9].covariates, (std::vector<int>{0, 1, 2, 3, 5, 6, 7, 8}));
    EXPECT_TRUE(fit.params[4].constant);
    EXPECT_TRUE(fit.params[10].covariates.empty());  // P11-P13 independent
    EXPECT_TRUE(fit.params[12].covariates.empty());
    EXPECT_FALSE(fit.params[12].individualEffect);
    SplitMix rng(1);
    EXPECT_EQ(drawAkagiParams(fit, rng).branchNum, 5);
}

TEST(AkagiModel, SameSeedSameFitAndDraws) {
    McmcOptions o;
    o.burnIn = 200, o.samples = 50;
    ObservationTable t = akagiSpeciesTable("aomoji");
    AkagiFit a = fitAkagiModel(t, o), b = fitAkagiModel(t, o);
    SplitMix ra(3), rb(3);
    for (int i = 0; i < 5; ++i) {
        AkagiParams pa = drawAkagiParams(a, ra), pb = drawAkagiParams(b, rb);
        for (int k = 0; k < kAkagiParamCount; ++k) EXPECT_EQ(pa[k], pb[k]);
    }
}

struct SpeciesForm {
    double crownRatio = 0, widest = 0, mainAxisShare = 0, straightness = 0;
};

SpeciesForm growSpecies(const std::string& name) {
    McmcOptions o;
    o.burnIn = 1500, o.samples = 300;
    AkagiFit fit = fitAkagiModel(akagiSpeciesTable(name), o);
    for (const AkagiParamFit& f : fit.params) {
        if (f.constant) continue;
        EXPECT_GT(f.acceptance, 0.15) << name;  // the adapted random walks move
        EXPECT_LT(f.acceptance, 0.8) << name;
    }
    SplitMix rng(11);
    SpeciesForm form;
    const int trees = 6;
    for (int n = 0; n < trees;) {
        AkagiParams p = drawAkagiParams(fit, rng);
        for (int k = 0; k < kAkagiParamCount; ++k) EXPECT_EQ(akagiParamProblem(k, p[k]), "");
        AkagiTree t = generateAkagiTree(p, n, 40);
        if (!isPlausible(t)) continue;
        form.crownRatio += t.stats.crownWidth / t.stats.height / trees;
        form.widest += t.stats.widestRelativeHeight / trees;
        form.mainAxisShare += t.stats.mainAxisLength / t.stats.trunkLength / trees;
        form.straightness += t.stats.trunkStraightness / trees;
        ++n;
    }
    return form;
}

TEST(AkagiModel, ShippedSpeciesFitAndKeepTheirForm) {
    EXPECT_EQ(akagiSpeciesNames(), (std::vector<std::string>{"akagashi", "akaezomatsu", "aomoji",
                                                             "keyaki", "yabunikkei"}));
    // Picea glehnii: monopodial, straight leader, narrow conical crown widest near the base.
    SpeciesForm spruce = growSpecies("akaezomatsu");
    EXPECT_GT(spruce.straightness, 0.97);
    EXPECT_GT(spruce.mainAxisShare, 0.99);
    EXPECT_LT(spruce.crownRatio, 0.5);
    EXPECT_LT(spruce.widest, 0.3);
    // Zelkova: sympodial vase, broad crown widest high up, the main axis gives way early.
    SpeciesForm zelkova = growSpecies("keyaki");
    EXPECT_GT(zelkova.crownRatio, 0.6);
    EXPECT_GT(zelkova.widest, 0.45);
    EXPECT_LT(zelkova.mainAxisShare, 0.7);
    // The broadleaves in between: rounded crowns wider than the spruce's.
    for (const char* name : {"akagashi", "aomoji", "yabunikkei"}) {
        SpeciesForm f = growSpecies(name);
        EXPECT_GT(f.crownRatio, spruce.crownRatio) << name;
        EXPECT_GT(f.widest, spruce.widest) << name;
    }
}

TEST(AkagiModel, GrowSpeciesReturnsAPlausibleTreeAndRejectsUnknownNames) {
    AkagiGrowOptions o;
    o.mcmc.burnIn = 500, o.mcmc.samples = 100;
    AkagiTree t = growAkagiSpecies("yabunikkei", 5, 30, o);
    std::string why;
    EXPECT_TRUE(isPlausible(t, &why)) << why;
    EXPECT_GE(t.attempts, 1);
    // Same seed, same tree; and the skeleton survives the file format's strict loader.
    AkagiTree again = growAkagiSpecies("yabunikkei", 5, 30, o);
    ASSERT_EQ(again.skeleton.nodes().size(), t.skeleton.nodes().size());
    for (size_t i = 0; i < t.skeleton.nodes().size(); ++i)
        EXPECT_EQ(again.skeleton.node(i).position, t.skeleton.node(i).position);
    SkeletonFileInfo info = akagiSkeletonInfo(t, "yabunikkei", 5);
    nlohmann::json j = skeletonToJson(t.skeleton, info);
    EXPECT_EQ(j["source"]["model"], "akagi");
    EXPECT_EQ(j["source"]["parameters"]["Height"], t.params.height);
    Skeleton back = parseSkeleton(j, "tree.json");
    ASSERT_EQ(back.nodes().size(), t.skeleton.nodes().size());
    for (size_t i = 0; i < back.nodes().size(); ++i) {
        EXPECT_EQ(back.node(i).position, t.skeleton.node(i).position);
        EXPECT_EQ(back.node(i).birthTime, t.skeleton.node(i).birthTime);
    }
    try {
        growAkagiSpecies("sugi", 5, 30, o);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("unknown species 'sugi' (expected one of akagashi"),
                  std::string::npos);
    }
    EXPECT_THROW(growAkagiSpecies("/nonexistent/table.csv", 5, 30, o), InputError);
    EXPECT_THROW(growAkagiSpecies("keyaki", 5, 0, o), InputError);
}

TEST(AkagiModel, UsersCanGrowFromTheirOwnTableFile) {
    // A dichotomous species (MainGrowth ~ 0: 100 x MainGrowth < 1, the main child is a leaf).
    std::string path = scratchPath("akagi-own-table.csv").string();
    {
        std::ofstream out(path);
        out << "# two-way forking shrub\n"
               "tree,Height,Radius,LeafNum,LeafSize,BranchNum,MainGrowth,MainAngle,MainRotation,"
               "SubGrowth,SubAngle,BranchPoint,Horizontal,GrowthGain\n";
        const char* rows[] = {"a,3.0,0.05,4,0.05,3,0.0010,0,90,0.49,30,0.20,0.1,0.05",
                              "a,3.0,0.05,5,0.05,3,0.0012,1,92,0.50,32,0.22,0.1,0.04",
                              "b,3.4,0.06,4,0.06,3,0.0008,-1,88,0.48,28,0.18,0.2,0.06",
                              "b,3.4,0.06,6,0.06,3,0.0011,0,91,0.50,31,0.21,0.1,0.05",
                              "c,2.7,0.04,5,0.05,3,0.0009,2,89,0.49,29,0.19,0.1,0.05",
                              "c,2.7,0.04,4,0.05,3,0.0010,-2,90,0.47,30,0.20,0.2,0.04"};
        for (const char* r : rows) out << r << "\n";
    }
    AkagiGrowOptions o;
    o.mcmc.burnIn = 500, o.mcmc.samples = 100;
    AkagiTree t = growAkagiSpecies(path, 3, 20, o);
    std::filesystem::remove(path);
    EXPECT_TRUE(isPlausible(t));
    // Dichotomous: the root's main child is a leaf, the tree forks into two equal laterals.
    ASSERT_EQ(t.segments[0].children.size(), 2u);
    EXPECT_NEAR(t.stats.mainAxisLength, t.stats.firstForkHeight, 1e-12);
}

TEST(AkagiModel, BadMcmcOptionsAreInputErrors) {
    ObservationTable t = akagiSpeciesTable("keyaki");
    McmcOptions o;
    o.samples = 0;
    EXPECT_THROW(fitAkagiModel(t, o), InputError);
    o = {};
    o.burnIn = -1;
    EXPECT_THROW(fitAkagiModel(t, o), InputError);
}

}  // namespace
}  // namespace nenrin
