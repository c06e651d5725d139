// Kanayama hormone model: transport only toward the root, with the paper's recurrences.
#include "skeleton/sources/kanayama/kanayama_hormone.h"

#include <gtest/gtest.h>

#include <cmath>

namespace nenrin {
namespace {

// A small tree: 0 root; 1, 2 on 0; 3, 4 on 1; 5 on 2; 6 on 5.
const std::vector<int32_t> kParent{-1, 0, 0, 1, 1, 2, 5};

TEST(KanayamaHormone, FlowsOnlyTowardTheRoot) {
    // Only shoot 3 produces: hormone appears on 3 and its ancestors 1, 0, nowhere else.
    std::vector<double> previous(7, 0.0), production(7, 0.0);
    production[3] = 2.0;
    std::vector<uint8_t> alive(7, 1);
    double beta = 0.6, gamma = 0.5;
    std::vector<double> h = transportHormone(kParent, previous, production, alive, beta, gamma);
    EXPECT_DOUBLE_EQ(h[3], 2.0);
    EXPECT_DOUBLE_EQ(h[1], gamma * 2.0);
    EXPECT_DOUBLE_EQ(h[0], gamma * gamma * 2.0);
    for (int s : {2, 4, 5, 6}) EXPECT_EQ(h[s], 0.0) << "shoot " << s;
    // Monotone along the path to the root when gamma < 1 and nothing else is produced.
    EXPECT_GT(h[3], h[1]);
    EXPECT_GT(h[1], h[0]);
}

TEST(KanayamaHormone, PaperRecurrencesAndConservation) {
    std::vector<double> previous{1.0, 0.5, 0.25, 0.3, 0.2, 0.1, 0.4};
    std::vector<double> production{0, 0, 0, 0.7, 0.9, 0, 0.8};
    std::vector<uint8_t> alive(7, 1);
    double beta = 0.7, gamma = 0.4;
    std::vector<double> h = transportHormone(kParent, previous, production, alive, beta, gamma);
    // H_n = beta H_n0 + L dH on new shoots; H_o = beta H_o0 + gamma sum(H_n) below them.
    EXPECT_DOUBLE_EQ(h[3], beta * 0.3 + 0.7);
    EXPECT_DOUBLE_EQ(h[6], beta * 0.4 + 0.8);
    EXPECT_DOUBLE_EQ(h[5], beta * 0.1 + gamma * h[6]);
    EXPECT_DOUBLE_EQ(h[1], beta * 0.5 + gamma * (h[3] + h[4]));
    EXPECT_DOUBLE_EQ(h[0], beta * 1.0 + gamma * (h[1] + h[2]));
    // With no decay and full transfer the root holds everything ever made: conservation.
    std::vector<double> all = transportHormone(kParent, previous, production, alive, 1.0, 1.0);
    double total = 0;
    for (size_t i = 0; i < 7; ++i) total += previous[i] + production[i];
    EXPECT_NEAR(all[0], total, 1e-12);
}

TEST(KanayamaHormone, DeadShootsPassNothing) {
    std::vector<double> previous(7, 1.0), production(7, 1.0);
    std::vector<uint8_t> alive(7, 1);
    alive[5] = 0;  // cut: 6 still makes hormone but it cannot reach 2 through 5
    std::vector<double> h = transportHormone(kParent, previous, production, alive, 0.5, 0.5);
    EXPECT_EQ(h[5], 0.0);
    EXPECT_DOUBLE_EQ(h[2], 0.5 + 1.0);
}

TEST(KanayamaHormone, TerminalInheritsMore) {
    EXPECT_DOUBLE_EQ(inheritedHormone(2.0, true, 0.9, 0.3), 1.8);
    EXPECT_DOUBLE_EQ(inheritedHormone(2.0, false, 0.9, 0.3), 0.6);
}

}  // namespace
}  // namespace nenrin
