#include "skeleton/sources/kunii/kunii_stand.h"

#include <gtest/gtest.h>

#include <cmath>

#include "skeleton/sources/kunii/kunii_fell.h"
#include "skeleton/sources/kunii/kunii_stand_file.h"
#include "util/input_error.h"

namespace nenrin {
namespace {

/// A smaller plot than the default keeps the tests fast; 60 seedlings on 900 m^2 is the
/// default density.
StandOptions smallStand(uint64_t seed, double irradiance, int years) {
    StandOptions o;
    o.seed = seed;
    o.trees = 60;
    o.plotSize = 30;
    o.years = years;
    o.irradiance = irradiance;
    return o;
}

constexpr double kSplit = 0.5;  // g < 0.5: shade tolerant

TEST(KuniiStand, ToleranceDominatesInShadeIntoleranceInSun) {
    // Same species mix (g uniform in [0.05, 1]); only I0 differs. Share of the living
    // biomass held by tolerant species after 60 years, for every seed.
    for (uint64_t seed : {1, 2, 3}) {
        StandComposition shade = standComposition(simulateStand(smallStand(seed, 0.3, 60)), kSplit);
        StandComposition sun = standComposition(simulateStand(smallStand(seed, 1.0, 60)), kSplit);
        EXPECT_GT(shade.tolerantShare(), 0.7) << "seed " << seed;
        EXPECT_LT(sun.tolerantShare(), 0.3) << "seed " << seed;
        EXPECT_LT(shade.meanSpecies, sun.meanSpecies) << "seed " << seed;
    }
}

TEST(KuniiStand, LoweringAndRaisingIrradianceShowsHysteresis) {
    // Both stands end 60 years at the same intermediate I0 = 0.35; one came down from full
    // sun (50 years at 1.0, 10-year ramp), the other up from shade (0.25). The canopy each
    // built keeps its species: intolerant from above, tolerant from below.
    for (uint64_t seed : {1, 2}) {
        StandOptions fromSun = smallStand(seed, 1.0, 120);
        fromSun.schedule = {{0, 1.0}, {50, 1.0}, {60, 0.35}};
        StandOptions fromShade = fromSun;
        fromShade.schedule = {{0, 0.25}, {50, 0.25}, {60, 0.35}};
        double down = standComposition(simulateStand(fromSun), kSplit).tolerantShare();
        double up = standComposition(simulateStand(fromShade), kSplit).tolerantShare();
        EXPECT_LT(down, 0.4) << "seed " << seed;
        EXPECT_GT(up, 0.6) << "seed " << seed;
    }
}

TEST(KuniiStand, SuppressedTreesLayNarrowerRingsThanDominantOnes) {
    for (uint64_t seed : {1, 2, 3}) {
        Stand stand = simulateStand(smallStand(seed, 1.0, 80));
        auto meanLastRings = [&](uint32_t id) {
            std::vector<double> w = standTreeRingWidths(stand.trees[id]);
            double sum = 0;
            for (size_t k = w.size() - 10; k < w.size(); ++k) sum += w[k];
            return sum / 10;
        };
        uint32_t dominant = pickStandTree(stand, TreePick::Dominant);
        uint32_t suppressed = pickStandTree(stand, TreePick::Suppressed);
        EXPECT_NE(dominant, suppressed);
        EXPECT_LT(meanLastRings(suppressed), 0.5 * meanLastRings(dominant)) << "seed " << seed;
        EXPECT_LT(stand.trees[suppressed].last().height, stand.trees[dominant].last().height);
    }
}

TEST(KuniiStand, SeedlingsGerminateOnlyWhereTheGroundIsLight) {
    Stand stand = simulateStand(smallStand(4, 1.0, 60));
    int germinated = 0;
    for (const StandTree& t : stand.trees) {
        if (t.birthYear == 0) continue;
        ++germinated;
        // Recomputed from the stand's records of the year before, independently of the
        // simulation's own bookkeeping.
        double light = groundLight(stand, t.x, t.y, t.birthYear - 1);
        EXPECT_GT(light, stand.options.germinationLight) << "tree " << t.id;
        EXPECT_NEAR(light, t.germinationLight, 1e-12) << "tree " << t.id;
    }
    EXPECT_GT(germinated, 20);
    // Under a threshold above the sun itself nothing germinates.
    StandOptions dark = smallStand(4, 1.0, 30);
    dark.germinationLight = 1.0;
    Stand none = simulateStand(dark);
    EXPECT_EQ(none.trees.size(), 60u);
}

TEST(KuniiStand, LivingTreesStayAboveTheirCompensationPointAndNeverShrink) {
    Stand stand = simulateStand(smallStand(5, 0.6, 60));
    int dead = 0;
    for (const StandTree& t : stand.trees) {
        dead += !t.alive();
        const TreeYear* previous = &t.initial;
        for (const TreeYear& y : t.history) {
            EXPECT_GT(y.irradiance, compensationIrradiance(stand.options.law, t.species));
            EXPECT_GE(y.stemRadius, previous->stemRadius);
            EXPECT_GE(y.height, previous->height);
            EXPECT_GE(y.crownBase, previous->crownBase);  // dead branches do not come back
            EXPECT_LT(y.crownBase, y.height);
            previous = &y;
        }
        size_t lived =
            static_cast<size_t>((t.alive() ? stand.options.years : t.deathYear) - t.birthYear);
        EXPECT_EQ(t.history.size(), lived);
    }
    EXPECT_GT(dead, 0);  // competition kills
}

TEST(KuniiStand, SameSeedSameStandBitwise) {
    StandOptions o = smallStand(6, 0.8, 40);
    std::string a = standToJson(simulateStand(o)).dump();
    std::string b = standToJson(simulateStand(o)).dump();
    EXPECT_EQ(a, b);
    o.seed = 7;
    EXPECT_NE(a, standToJson(simulateStand(o)).dump());
}

TEST(KuniiStand, ReportsProgressEveryYear) {
    int calls = 0, last = 0;
    simulateStand(smallStand(1, 1.0, 12), [&](int year, int years) {
        ++calls;
        last = year;
        EXPECT_EQ(years, 12);
    });
    EXPECT_EQ(calls, 12);
    EXPECT_EQ(last, 12);
}

TEST(KuniiStand, BadOptionsAreInputErrorsNamingTheParameter) {
    auto expectError = [](StandOptions o, const std::string& parameter) {
        try {
            simulateStand(o);
            FAIL() << parameter;
        } catch (const InputError& e) {
            EXPECT_EQ(e.where(), parameter) << e.what();
        }
    };
    StandOptions o;
    o.years = -1;
    expectError(o, "years");
    o = StandOptions{};
    o.irradiance = std::nan("");
    expectError(o, "irradiance");
    o = StandOptions{};
    o.law.f = 0;
    expectError(o, "law.f");
    o = StandOptions{};
    o.schedule = {{10, 1.0}, {5, 0.5}};
    expectError(o, "schedule[1].year");
    o = StandOptions{};
    o.plotSize = -3;
    expectError(o, "plot_size");
}

TEST(KuniiStand, PresetsAreValidAndUnknownOnesAreErrors) {
    for (const std::string& name : standPresetNames())
        EXPECT_NO_THROW(validateStandOptions(standPreset(name))) << name;
    EXPECT_EQ(standPreset("cooling").irradianceAt(119), standPreset("warming").irradianceAt(119));
    EXPECT_GT(standPreset("cooling").irradianceAt(10), standPreset("warming").irradianceAt(10));
    EXPECT_THROW(standPreset("boreal"), InputError);
}

TEST(KuniiStand, IrradianceScheduleInterpolates) {
    StandOptions o;
    o.schedule = {{10, 1.0}, {20, 0.5}};
    EXPECT_DOUBLE_EQ(o.irradianceAt(0), 1.0);
    EXPECT_DOUBLE_EQ(o.irradianceAt(15), 0.75);
    EXPECT_DOUBLE_EQ(o.irradianceAt(50), 0.5);
}

}  // namespace
}  // namespace nenrin
