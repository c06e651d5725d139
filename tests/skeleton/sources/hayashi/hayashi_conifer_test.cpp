// Hayashi & Takahashi conifer model: the statistics the paper measured (Table 1, Figs. 2-3,
// 6-12) come out of the generated trees, and the skeleton is a valid growth history.
#include "skeleton/sources/hayashi/hayashi_conifer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

#include "skeleton/skeleton_file.h"
#include "skeleton/skeleton_writer.h"
#include "skeleton/sources/hayashi/rodrigues_rotation.h"
#include "skeleton/sources/hayashi/seasonal_height_growth.h"
#include "skeleton/sources/hayashi/truncated_normal.h"
#include "util/input_error.h"

namespace nenrin {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = HayashiOptions::kDegree;

HayashiOptions firstOrderOnly(const std::string& preset, uint64_t seed) {
    HayashiOptions o = hayashiPreset(preset);
    o.seed = seed;
    o.maxOrder = 1;
    return o;
}

Vec3 firstDirection(const Skeleton& sk, int32_t chain) {
    const auto& s = sk.segment(sk.chain(chain).firstSegment);
    return normalize(sk.end(s) - sk.start(s));
}

/// The paper's spiral analysis (3.3, Fig. 9, Table 1) on a generated tree: the rotation from
/// each first-order branch to the next (read from the skeleton's geometry, turning clockwise
/// seen from above), summed over whole growth years 1 .. years-2.
struct SpiralSample {
    double rotation = 0;  // rad
    int branches = 0;
    int years = 0;
    std::vector<double> divergences;  // rad
};

void addSpiralSample(const HayashiTree& tree, int years, SpiralSample& out) {
    const Skeleton& sk = tree.skeleton;
    const HayashiBranchRecord* previous = nullptr;
    for (const auto& r : tree.firstOrder) {
        bool inRange = r.birthTime >= 1 && r.birthTime < years - 1;
        if (inRange) {
            ASSERT_NE(r.chain, kNone) << "a branch of a full year is missing from the skeleton";
            ASSERT_NE(previous, nullptr);
            Vec3 a = firstDirection(sk, previous->chain), b = firstDirection(sk, r.chain);
            double d = std::atan2(a.y, a.x) - std::atan2(b.y, b.x);  // clockwise positive
            d -= 2 * kPi * std::floor(d / (2 * kPi));
            out.rotation += d;
            out.branches += 1;
            out.divergences.push_back(d);
        }
        previous = &r;
    }
    out.years += years - 2;
}

struct Summary {
    double mean, sd, min, max;
};
Summary summarize(const std::vector<double>& v) {
    double s = 0, s2 = 0, lo = 1e300, hi = -1e300;
    for (double x : v) {
        s += x;
        s2 += x * x;
        lo = std::min(lo, x);
        hi = std::max(hi, x);
    }
    double n = static_cast<double>(v.size()), mean = s / n;
    return {mean, std::sqrt(s2 / n - mean * mean), lo, hi};
}

SpiralSample spiralOverSeeds(HayashiOptions o, int seeds) {
    SpiralSample sample;
    for (int seed = 1; seed <= seeds; ++seed) {
        o.seed = static_cast<uint64_t>(seed);
        addSpiralSample(growHayashiConifer(o), o.years, sample);
    }
    return sample;
}

// Table 1: 3.19 turns per year and 2.10 branches per turn (17 sugi). Turns per year is set by
// the model per growing season, so it is near-exact (the sum over whole years misses at most
// one divergence at each end: < 0.05 turns/year over 18 years); branches per turn is a sampling
// statistic: 40 trees x ~120 branches, divergence sd 73 deg gives a standard error of ~0.012,
// so 0.04 is > 3 standard errors.
TEST(HayashiConifer, SugiSpiralMatchesTable1Means) {
    SpiralSample s = spiralOverSeeds(firstOrderOnly("sugi", 1), 40);
    double turns = s.rotation / (2 * kPi);
    EXPECT_NEAR(turns / s.years, 3.19, 0.05);
    EXPECT_NEAR(s.branches / turns, 2.10, 0.04);
}

// The paper's divergence figures for sugi (Fig. 2: mean 173, sd 73, min 33, max 293 deg); the
// mean is tied to branches per turn: 360 / 2.10 = 171.4 deg. Sampling error of the mean
// ~1 deg, of the sd ~0.8 deg.
TEST(HayashiConifer, SugiDivergenceAnglesFollowThePaper) {
    SpiralSample s = spiralOverSeeds(firstOrderOnly("sugi", 1), 40);
    Summary d = summarize(s.divergences);
    EXPECT_NEAR(d.mean / kDeg, 360 / 2.10, 3.0);
    EXPECT_NEAR(d.sd / kDeg, 73, 3.0);
    EXPECT_GE(d.min / kDeg, 33 - 1e-6);
    EXPECT_LE(d.max / kDeg, 293 + 1e-6);
    EXPECT_LT(d.min / kDeg, 45);  // the range is used, not just the middle
    EXPECT_GT(d.max / kDeg, 280);
}

TEST(HayashiConifer, HinokiDivergenceAnglesFollowThePaper) {
    SpiralSample s = spiralOverSeeds(firstOrderOnly("hinoki", 1), 40);
    Summary d = summarize(s.divergences);
    EXPECT_NEAR(d.mean / kDeg, 164, 3.0);
    EXPECT_NEAR(d.sd / kDeg, 52, 3.0);
    EXPECT_GE(d.min / kDeg, 52 - 1e-6);
    EXPECT_LE(d.max / kDeg, 244 + 1e-6);
}

// Other trees of Table 1: No. 10 (2.4 turns/year, 2.4 branches/turn), No. 2 (5.0, 1.9).
TEST(HayashiConifer, RequestedTurnsAndBranchesPerTurnComeOut) {
    for (auto [tpy, bpt] : {std::pair{2.4, 2.4}, std::pair{5.0, 1.9}}) {
        HayashiOptions o = firstOrderOnly("sugi", 1);
        o.turnsPerYear = tpy;
        o.branchesPerTurn = bpt;
        SpiralSample s = spiralOverSeeds(o, 30);
        double turns = s.rotation / (2 * kPi);
        EXPECT_NEAR(turns / s.years, tpy, 0.05) << tpy << " turns/year";
        EXPECT_NEAR(s.branches / turns, bpt, 0.05) << bpt << " branches/turn";
        double perYear = static_cast<double>(s.branches) / s.years;
        EXPECT_NEAR(perYear, tpy * bpt, 0.03 * tpy * bpt);
    }
}

// Eq. 2: fit a of y = a (1 - z)^0.5 by least squares to the living first-order branches
// (length measured along the skeleton chain, normalised by the tree height). Lengths scatter
// by 10 % about the curve; pooled over 20 trees (~1000 branches) the fit is within 2 %.
double fitCrownCoefficient(const HayashiOptions& base, int seeds) {
    double num = 0, den = 0;
    HayashiOptions o = base;
    for (int seed = 1; seed <= seeds; ++seed) {
        o.seed = static_cast<uint64_t>(seed);
        HayashiTree t = growHayashiConifer(o);
        for (const auto& r : t.firstOrder) {
            if (r.chain == kNone || r.deathTime != kNeverDies) continue;
            const auto& c = t.skeleton.chain(r.chain);
            double len = 0;
            for (uint32_t i = 0; i < c.segmentCount; ++i) {
                const auto& s = t.skeleton.segment(c.firstSegment + i);
                len += length(t.skeleton.end(s) - t.skeleton.start(s));
            }
            double y = len / t.height, w = std::sqrt(1 - r.height / t.height);
            num += y * w;
            den += w * w;
        }
    }
    return num / den;
}

TEST(HayashiConifer, FirstOrderBranchesFollowTheParabolicCrown) {
    EXPECT_NEAR(fitCrownCoefficient(firstOrderOnly("sugi", 1), 20), 0.30, 0.006);
    HayashiOptions o = firstOrderOnly("hinoki", 1);
    o.crownCoefficient = 0.25;
    EXPECT_NEAR(fitCrownCoefficient(o, 20), 0.25, 0.005);
}

// Fig. 9: height growth is fast in spring and zero in autumn/winter. No first-order branch is
// born outside the growing season, the trunk gains no height in winter, and within each year
// branch heights crowd towards the top of the year's shoot: with rotation even in time and
// growth 1 - (1 - u)^p, a share 2^(-1/p) of a year's branches sit in the upper half of its
// growth (0.707 for p = 2; 0.5 without seasonality). ~2000 branches: standard error 0.01.
double upperHalfShare(HayashiOptions o, int seeds) {
    int upper = 0, all = 0;
    for (int seed = 1; seed <= seeds; ++seed) {
        o.seed = static_cast<uint64_t>(seed);
        HayashiTree t = growHayashiConifer(o);
        for (const auto& r : t.firstOrder) {
            double frac = r.birthTime - std::floor(r.birthTime);
            EXPECT_LE(frac, o.growingSeason + 1e-9) << "a branch born in winter";
            double h0 = t.yearStartHeights[r.year], h1 = t.yearStartHeights[r.year + 1];
            EXPECT_GE(r.height, h0 - 1e-9);
            EXPECT_LE(r.height, h1 + 1e-9);
            upper += r.height > 0.5 * (h0 + h1);
            all += 1;
        }
    }
    return static_cast<double>(upper) / all;
}

TEST(HayashiConifer, BranchHeightsClusterByYear) {
    HayashiOptions o = firstOrderOnly("sugi", 1);
    EXPECT_NEAR(upperHalfShare(o, 15), std::pow(2.0, -1 / o.seasonShape), 0.035);
    o.seasonShape = 1;  // no spring flush: the control
    EXPECT_NEAR(upperHalfShare(o, 15), 0.5, 0.035);

    HayashiTree t = growHayashiConifer(firstOrderOnly("sugi", 3));
    SeasonalHeightGrowth growth(t.yearStartHeights, 0.5, 2);
    for (int y = 0; y < 19; ++y) {
        EXPECT_EQ(growth.heightAt(y + 0.5), growth.heightAt(y + 0.99)) << "winter of year " << y;
        EXPECT_GT(growth.heightAt(y + 0.25) - growth.heightAt(y),
                  growth.heightAt(y + 0.5) - growth.heightAt(y + 0.25))
            << "spring growth is faster";
    }
    // The trunk's node times say the same: nothing is born between season end and spring.
    for (uint32_t i = 0; i <= t.skeleton.trunkSegmentCount(); ++i) {
        double birth = t.skeleton.node(i).birthTime;
        EXPECT_LE(birth - std::floor(birth), 0.5 + 1e-9) << "trunk node born in winter";
    }
}

// Fig. 12: a whorled pine has its branches at discrete heights, one whorl a year.
TEST(HayashiConifer, PineBranchesComeInWhorls) {
    HayashiOptions o = firstOrderOnly("pine", 5);
    HayashiTree t = growHayashiConifer(o);
    std::map<double, std::vector<const HayashiBranchRecord*>> whorls;
    for (const auto& r : t.firstOrder) whorls[r.height].push_back(&r);
    ASSERT_EQ(whorls.size(), static_cast<size_t>(o.years - 1));
    int y = 1;
    for (const auto& [h, members] : whorls) {
        EXPECT_EQ(h, t.yearStartHeights[y]) << "whorl " << y << " is not at a year's top";
        EXPECT_GE(members.size(), static_cast<size_t>(o.whorlMin));
        EXPECT_LE(members.size(), static_cast<size_t>(o.whorlMax));
        for (const auto* r : members) EXPECT_EQ(r->birthTime, y);
        // Spread around the stem: no two branches of a whorl closer than 360/n - 6 sd.
        std::vector<double> az;
        for (const auto* r : members) az.push_back(r->azimuth);
        std::sort(az.begin(), az.end());
        double n = static_cast<double>(az.size());
        for (size_t i = 0; i < az.size(); ++i) {
            double gap = i + 1 < az.size() ? az[i + 1] - az[i] : az[0] + 2 * kPi - az[i];
            EXPECT_GT(gap, 2 * kPi / n - 6 * o.whorlJitter) << "whorl " << y;
        }
        ++y;
    }
}

// Section 6.1: every 2nd..4th order branch leaves its parent at alpha = 80 deg, turned by a
// random beta (the turns cover the circle).
TEST(HayashiConifer, SideBranchesMakeAlphaWithTheirParent) {
    HayashiOptions o = hayashiPreset("sugi");
    o.years = 5;
    HayashiTree t = growHayashiConifer(o);
    const Skeleton& sk = t.skeleton;
    size_t checked = 0;
    int quadrants[4] = {0, 0, 0, 0};
    for (size_t c = 1; c < sk.chains().size(); ++c) {
        const auto& chain = sk.chain(c);
        if (chain.order < 2) continue;
        const auto& s = sk.segment(chain.firstSegment);
        const auto& p = sk.segment(s.parent);
        Vec3 d = normalize(sk.end(s) - sk.start(s)), pd = normalize(sk.end(p) - sk.start(p));
        ASSERT_NEAR(std::acos(std::clamp(dot(d, pd), -1.0, 1.0)), 80 * kDeg, 1e-9) << "chain " << c;
        // beta: the side of the parent the branch points to, relative to the up side.
        Vec3 up = normalize(cross(cross(pd, {0, 0, 1}), pd));
        Vec3 perp = d - pd * dot(d, pd);
        double beta = std::atan2(dot(cross(up, perp), pd), dot(up, perp));
        quadrants[static_cast<int>(std::floor((beta + kPi) / (kPi / 2))) & 3] += 1;
        ++checked;
    }
    EXPECT_EQ(checked, t.chainsPerOrder[2] + t.chainsPerOrder[3] + t.chainsPerOrder[4]);
    EXPECT_GT(t.chainsPerOrder[4], 1000u);
    for (int q : quadrants) EXPECT_NEAR(q, checked / 4.0, 0.05 * checked);
}

// The crown base rises with the tree: first-order branches below (1 - crown ratio) x height are
// dead, with the death time when the trunk reached height / (1 - crown ratio); their side
// branches die with them; all others live.
TEST(HayashiConifer, DeadBranchesAreExactlyThoseBelowTheCrownBase) {
    HayashiOptions o = hayashiPreset("sugi");
    o.years = 12;
    o.maxOrder = 2;
    HayashiTree t = growHayashiConifer(o);
    SeasonalHeightGrowth growth(t.yearStartHeights, o.growingSeason, o.seasonShape);
    EXPECT_NEAR(t.crownBase, (1 - o.crownRatio) * t.height, 1e-12);
    int dead = 0, alive = 0;
    std::map<int32_t, double> deathOfChain;
    for (const auto& r : t.firstOrder) {
        if (r.chain == kNone) continue;
        bool below = r.height < t.crownBase;
        EXPECT_EQ(r.deathTime != kNeverDies, below) << "branch at " << r.height;
        if (below) {
            ++dead;
            EXPECT_GT(r.deathTime, r.birthTime);
            EXPECT_LE(r.deathTime, o.years);
            EXPECT_NEAR(growth.heightAt(r.deathTime), r.height / (1 - o.crownRatio), 1e-9);
        } else {
            ++alive;
        }
        deathOfChain[r.chain] = r.deathTime;
    }
    EXPECT_GT(dead, 10);
    EXPECT_GT(alive, 10);
    const Skeleton& sk = t.skeleton;
    for (size_t c = 1; c < sk.chains().size(); ++c) {
        const auto& chain = sk.chain(c);
        int32_t root = static_cast<int32_t>(c);
        while (sk.chain(root).order > 1) root = sk.chain(root).parentChain;
        double death = deathOfChain.at(root);
        for (uint32_t i = 0; i < chain.segmentCount; ++i) {
            const auto& s = sk.segment(chain.firstSegment + i);
            EXPECT_EQ(s.deathTime, death);
            EXPECT_EQ(s.diebackExponent, 1.0);
            // Dead branches stop lengthening: nothing on them is born after the death.
            EXPECT_LE(sk.node(s.to).birthTime, death);
        }
    }
}

void expectIdentical(const Skeleton& a, const Skeleton& b) {
    ASSERT_EQ(a.nodes().size(), b.nodes().size());
    ASSERT_EQ(a.segments().size(), b.segments().size());
    for (size_t i = 0; i < a.nodes().size(); ++i) {
        ASSERT_EQ(a.node(i).position, b.node(i).position) << i;
        ASSERT_EQ(a.node(i).birthTime, b.node(i).birthTime) << i;
        ASSERT_EQ(a.node(i).radius, b.node(i).radius) << i;
    }
    for (size_t i = 0; i < a.segments().size(); ++i) {
        ASSERT_EQ(a.segment(i).parent, b.segment(i).parent);
        ASSERT_EQ(a.segment(i).gamma, b.segment(i).gamma);
        ASSERT_EQ(a.segment(i).deathTime, b.segment(i).deathTime);
    }
}

TEST(HayashiConifer, SameSeedSameTreeOtherSeedOtherTree) {
    HayashiOptions o = hayashiPreset("sugi");
    o.years = 6;
    expectIdentical(growHayashiConifer(o).skeleton, growHayashiConifer(o).skeleton);
    HayashiOptions other = o;
    other.seed = 2;
    HayashiTree a = growHayashiConifer(o), b = growHayashiConifer(other);
    EXPECT_NE(a.firstOrder[0].azimuth, b.firstOrder[0].azimuth);
    EXPECT_NE(a.height, b.height);
    // Fewer orders leave the trunk and first-order branches where they were.
    HayashiOptions fewer = o;
    fewer.maxOrder = 1;
    HayashiTree c = growHayashiConifer(fewer);
    ASSERT_EQ(c.firstOrder.size(), a.firstOrder.size());
    for (size_t i = 0; i < a.firstOrder.size(); ++i) {
        EXPECT_EQ(c.firstOrder[i].azimuth, a.firstOrder[i].azimuth);
        EXPECT_EQ(c.firstOrder[i].length, a.firstOrder[i].length);
    }
}

// Every chain is a valid growth history: segments of non-zero length, birth times never
// decreasing, a branch starting on its parent segment no earlier than the parent got there,
// radii positive; and the file written for it loads back (the loader checks all that too).
void expectValidChains(const HayashiTree& t, int maxOrder) {
    const Skeleton& sk = t.skeleton;
    for (size_t c = 0; c < sk.chains().size(); ++c) {
        const auto& chain = sk.chain(c);
        ASSERT_LE(chain.order, maxOrder);
        for (uint32_t i = 0; i < chain.segmentCount; ++i) {
            const auto& s = sk.segment(chain.firstSegment + i);
            ASSERT_GE(length(sk.end(s) - sk.start(s)), 1e-6) << "chain " << c;
            ASSERT_GE(sk.node(s.to).birthTime, sk.node(s.from).birthTime) << "chain " << c;
            ASSERT_GT(sk.node(s.from).radius, 0);
            ASSERT_GT(sk.node(s.to).radius, 0);
        }
        if (c == 0) continue;
        const auto& first = sk.segment(chain.firstSegment);
        const auto& p = sk.segment(first.parent);
        ASSERT_EQ(p.chain, static_cast<uint32_t>(chain.parentChain));
        Vec3 a = sk.start(p), b = sk.end(p), q = sk.start(first);
        double f = std::clamp(dot(q - a, b - a) / lengthSquared(b - a), 0.0, 1.0);
        ASSERT_LT(length(q - lerp(a, b, f)), 1e-9) << "chain " << c << " is off its parent";
        double parentTime =
            sk.node(p.from).birthTime + f * (sk.node(p.to).birthTime - sk.node(p.from).birthTime);
        ASSERT_GE(sk.node(first.from).birthTime, parentTime - 1e-9) << "chain " << c;
    }
}

TEST(HayashiConifer, ChainsAreValidAndTheFileLoadsBack) {
    for (const auto& preset : hayashiPresetNames()) {
        HayashiOptions o = hayashiPreset(preset);
        o.years = 4;
        HayashiTree t = growHayashiConifer(o);
        SCOPED_TRACE(preset);
        expectValidChains(t, 4);
        Skeleton back = parseSkeleton(skeletonToJson(t.skeleton, {}), preset + ".json");
        EXPECT_EQ(back.segments().size(), t.skeleton.segments().size());
    }
    HayashiTree big = growHayashiConifer(firstOrderOnly("sugi", 9));
    expectValidChains(big, 1);
    EXPECT_EQ(big.chainsPerOrder[1] + 1, big.skeleton.chains().size());
    int perYear = 0;
    for (int n : big.branchesPerYear) perYear += n;
    EXPECT_EQ(static_cast<size_t>(perYear), big.firstOrder.size());
}

TEST(HayashiConifer, MaxOrderLimitsTheOrders) {
    HayashiOptions o = hayashiPreset("sugi");
    o.years = 5;
    for (int m = 1; m <= 4; ++m) {
        o.maxOrder = m;
        HayashiTree t = growHayashiConifer(o);
        for (int k = 1; k <= 4; ++k) EXPECT_EQ(t.chainsPerOrder[k] > 0, k <= m) << m << " " << k;
    }
}

TEST(HayashiOptionsTest, PresetsAndErrors) {
    EXPECT_EQ(hayashiPresetNames(), (std::vector<std::string>{"sugi", "hinoki", "pine"}));
    for (const auto& n : hayashiPresetNames())
        EXPECT_NO_THROW(validateHayashiOptions(hayashiPreset(n)));
    EXPECT_EQ(hayashiPreset("pine").arrangement, BranchArrangement::Whorled);
    try {
        hayashiPreset("larch");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "hayashi options: preset: unknown preset \"larch\": expected one of sugi, "
                  "hinoki, pine");
    }
    auto expectRejected = [](HayashiOptions o, const std::string& key) {
        try {
            growHayashiConifer(o);
            ADD_FAILURE() << key << " accepted";
        } catch (const InputError& e) {
            EXPECT_EQ(e.where(), key) << e.what();
        }
    };
    HayashiOptions o = hayashiPreset("sugi");
    o.years = 0;
    expectRejected(o, "years");
    o = hayashiPreset("sugi");
    o.heightGrowth = std::nan("");
    expectRejected(o, "height_growth");
    o = hayashiPreset("sugi");
    o.crownCoefficient = -0.3;
    expectRejected(o, "crown_coefficient");
    o = hayashiPreset("sugi");
    o.branchesPerTurn = 1.0;  // 360 deg divergence: outside 33..293
    expectRejected(o, "branches_per_turn");
    o = hayashiPreset("sugi");
    o.third.spacing = 0;
    expectRejected(o, "third_order.spacing");
    o = hayashiPreset("sugi");
    o.maxOrder = 5;
    expectRejected(o, "max_order");
}

TEST(HayashiOptionsTest, ReadsOverridesFromJson) {
    nlohmann::json j = parseJsonText(R"({"preset": "hinoki", "years": 7, "turns_per_year": 2.5,
        "divergence_sd": 40, "arrangement": "spiral", "clockwise": false,
        "third_order": {"spacing": 0.03, "profile": "constant"}})",
                                     "p.json");
    JsonReader r(j, "p.json");
    HayashiOptions o = readHayashiOptions(r, hayashiPreset("sugi"));
    EXPECT_EQ(o.years, 7);
    EXPECT_EQ(o.turnsPerYear, 2.5);
    EXPECT_NEAR(o.divergenceSd, 40 * kDeg, 1e-15);
    EXPECT_EQ(o.crownCoefficient, hayashiPreset("hinoki").crownCoefficient);
    EXPECT_FALSE(o.clockwise);
    EXPECT_EQ(o.third.spacing, 0.03);
    EXPECT_FALSE(o.third.parabolic);

    auto message = [](const std::string& text) {
        nlohmann::json j = parseJsonText(text, "p.json");
        JsonReader r(j, "p.json");
        try {
            readHayashiOptions(r, hayashiPreset("sugi"));
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    EXPECT_EQ(message(R"({"turns_per_yaer": 3})"),
              "p.json: turns_per_yaer: unknown key (misspelled? see the format documentation)");
    EXPECT_EQ(message(R"({"second_order": {"length": -1}})"),
              "p.json: second_order.length: expected a finite number > 0, found -1");
    EXPECT_EQ(message(R"({"preset": "fir"})"),
              "p.json: preset: unknown preset \"fir\": expected one of sugi, hinoki, pine");
    EXPECT_EQ(message(R"({"years": 0})"),
              "p.json: years: expected an integer in [1, 500], found 0");
}

// The options written into a file's provenance read back to the same tree (degrees go out and
// come back in; a seed past 2^53 survives as an integer).
TEST(HayashiOptionsTest, OptionsRoundTripThroughJson) {
    for (const auto& preset : hayashiPresetNames()) {
        HayashiOptions o = hayashiPreset(preset);
        o.seed = (1ull << 60) + 3;
        o.years = 3;
        o.maxOrder = 2;
        nlohmann::json j = hayashiOptionsToJson(o);
        JsonReader r(j, "source");
        HayashiOptions back = readHayashiOptions(r, HayashiOptions{});
        EXPECT_EQ(back.seed, o.seed);
        EXPECT_EQ(back.arrangement, o.arrangement);
        EXPECT_NEAR(back.divergenceSd, o.divergenceSd, 1e-15);
        HayashiTree a = growHayashiConifer(o), b = growHayashiConifer(back);
        ASSERT_EQ(a.skeleton.nodes().size(), b.skeleton.nodes().size()) << preset;
        for (size_t i = 0; i < a.skeleton.nodes().size(); ++i)
            ASSERT_NEAR(length(a.skeleton.node(i).position - b.skeleton.node(i).position), 0, 1e-9);
    }
}

// The shipped --params example: Table 1's tree No. 13 (3.8 turns/year, 2.0 branches/turn), a
// 7-year sugi planted in H4 (a = 0.33).
TEST(HayashiOptionsTest, ShippedParamsFileLoads) {
    HayashiOptions o = loadHayashiOptions(
        std::string(NENRIN_SOURCE_DIR) + "/scenes/trees/hayashi-sugi-no13.json", HayashiOptions{});
    EXPECT_EQ(o.years, 7);
    EXPECT_EQ(o.turnsPerYear, 3.8);
    EXPECT_EQ(o.branchesPerTurn, 2.0);
    EXPECT_EQ(o.crownCoefficient, 0.33);
    EXPECT_THROW(loadHayashiOptions("/nonexistent/params.json", o), InputError);
}

TEST(RodriguesRotation, TextbookFormula) {
    Vec3 z{0, 0, 1};
    Vec3 r = rotateAboutAxis({1, 0, 0}, z, kPi / 2);
    EXPECT_NEAR(r.x, 0, 1e-15);
    EXPECT_NEAR(r.y, 1, 1e-15);
    // About (1,1,1)/sqrt3 by 120 deg the axes cycle x -> y -> z.
    Vec3 k = normalize(Vec3{1, 1, 1});
    Vec3 c = rotateAboutAxis({1, 0, 0}, k, 2 * kPi / 3);
    EXPECT_NEAR(c.x, 0, 1e-12);
    EXPECT_NEAR(c.y, 1, 1e-12);
    EXPECT_NEAR(c.z, 0, 1e-12);
    // Side branches keep alpha to the axis for every beta.
    Vec3 axis = normalize(Vec3{0.3, -0.2, 0.9});
    for (double beta : {0.0, 1.0, 2.5, 4.0}) {
        Vec3 d = sideBranchDirection(axis, 80 * kDeg, beta);
        EXPECT_NEAR(length(d), 1, 1e-12);
        EXPECT_NEAR(std::acos(dot(d, axis)), 80 * kDeg, 1e-12);
    }
}

TEST(TruncatedNormalTest, MatchesRequestedMoments) {
    TruncatedNormal sugi = TruncatedNormal::fromMoments(171.43, 73, 33, 293);
    EXPECT_NEAR(sugi.mean(), 171.43, 1e-6);
    EXPECT_NEAR(sugi.sd(), 73, 1e-6);
    TruncatedNormal narrow = TruncatedNormal::fromMoments(100, 10, 0, 360);
    EXPECT_NEAR(narrow.location(), 100, 1e-6);
    EXPECT_NEAR(narrow.scale(), 10, 1e-6);
    SplitMix rng(4);
    std::vector<double> draws;
    for (int i = 0; i < 20000; ++i) draws.push_back(sugi.draw(rng));
    Summary s = summarize(draws);
    EXPECT_NEAR(s.mean, 171.43, 1.5);  // standard error 0.5
    EXPECT_NEAR(s.sd, 73, 1.5);
    EXPECT_GE(s.min, 33);
    EXPECT_LE(s.max, 293);
}

}  // namespace
}  // namespace nenrin
