#include "common/analysis/friedman.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace kapfix {
namespace {

// Three treatments on five blocks, no ties. Within every block A < B < C except block 4
// (A 3.1 > B 3.0), so the rank sums are A 6, B 9, C 15. By the mean-rank form
// Q = 12n / (k(k + 1)) · Σ(R̄_j − (k + 1)/2)² = 5 · ((1.2 − 2)² + (1.8 − 2)² + (3 − 2)²) = 8.4;
// with 2 dof the χ² upper tail is exp(−Q/2) = 0.0149956.
const std::vector<std::vector<double>> kBlocks = {
    {1.0, 2.0, 1.5, 3.1, 2.2}, {2.5, 3.5, 2.9, 3.0, 4.1}, {3.3, 4.0, 3.8, 4.4, 4.9}};

TEST(FriedmanTest, HandExampleGivesChiSquare) {
  EXPECT_NEAR(Friedman(kBlocks).chi_square, 8.4, 1e-12);
}

TEST(FriedmanTest, HandExampleGivesPValueFromChiSquareTwoDof) {
  EXPECT_NEAR(Friedman(kBlocks).p_value, std::exp(-8.4 / 2), 1e-12);
}

TEST(FriedmanTest, KendallWIsChiSquareOverNTimesKMinusOne) {
  EXPECT_NEAR(Friedman(kBlocks).kendall_w, 8.4 / 10.0, 1e-12);
}

TEST(FriedmanTest, MeanRanksFollowTreatments) {
  const FriedmanResult r = Friedman(kBlocks);
  ASSERT_EQ(r.mean_ranks.size(), 3U);
  EXPECT_DOUBLE_EQ(r.mean_ranks[0], 1.2);
  EXPECT_DOUBLE_EQ(r.mean_ranks[2], 3.0);
}

// Two treatments, a tie in one of three blocks: ranks (1.5, 1.5), (1, 2), (1, 2); R = 3.5, 5.5.
// By the general form for ties, (k − 1) Σ(R_j − n(k + 1)/2)² / (Σ r² − nk(k + 1)²/4):
// Σ(R_j − 4.5)² = 2, Σ r² = 2 · 2.25 + 2 · 5 = 14.5, nk(k + 1)²/4 = 13.5, so χ² = 2 / 1 = 2
// (the uncorrected 4/3 over the correction 1 − 6 / (3 · 6) = 2/3 agrees).
TEST(FriedmanTest, TiesWithinABlockAreCorrected) {
  EXPECT_NEAR(Friedman({{1, 1, 1}, {1, 2, 2}}).chi_square, 2.0, 1e-12);
}

TEST(FriedmanTest, AllTiedGivesPOne) { EXPECT_EQ(Friedman({{2, 2}, {2, 2}}).p_value, 1.0); }

TEST(FriedmanTest, UnequalBlockCountsAreRefused) {
  EXPECT_THROW(Friedman({{1, 2, 3}, {1, 2}}), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
