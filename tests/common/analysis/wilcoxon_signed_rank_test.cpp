#include "common/analysis/wilcoxon_signed_rank.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace kapfix {
namespace {

// Differences a − b = 2, 3, −1, 4, 6, −0.5, 8; ranks by |d|: 0.5→1, 1→2, 2→3, 3→4, 4→5,
// 6→6, 8→7. W− = 1 + 2 = 3, W+ = 25. Subsets of {1…7} with a sum ≤ 3: {}, {1}, {2}, {3},
// {1,2} = 5 of 128, and as many with a sum ≥ 25: two-sided p = 10 / 128 = 0.078125.
const std::vector<double> kA = {8, 12, 9, 15, 10, 7, 14};
const std::vector<double> kB = {6, 9, 10, 11, 4, 7.5, 6};

TEST(WilcoxonSignedRankTest, HandExampleGivesRankSums) {
  const WilcoxonResult r = WilcoxonSignedRank(kA, kB);
  EXPECT_DOUBLE_EQ(r.w_plus, 25.0);
  EXPECT_DOUBLE_EQ(r.w_minus, 3.0);
}

TEST(WilcoxonSignedRankTest, HandExampleGivesExactPValue) {
  const WilcoxonResult r = WilcoxonSignedRank(kA, kB);
  EXPECT_TRUE(r.exact);
  EXPECT_NEAR(r.p_value, 10.0 / 128.0, 1e-12);
}

// Published tables: n = 5 with every difference positive is the smallest two-sided p
// possible, 2 / 32 = 0.0625 (not significant at 5 %, the classic trap).
TEST(WilcoxonSignedRankTest, FiveAllPositiveGivesTableValue) {
  EXPECT_NEAR(WilcoxonSignedRank({2, 3, 4, 5, 6}, {1, 1, 1, 1, 1}).p_value, 0.0625, 1e-12);
}

TEST(WilcoxonSignedRankTest, RankBiserialIsOneWhenEveryPairIsAbove) {
  EXPECT_DOUBLE_EQ(WilcoxonSignedRank({2, 3, 4}, {1, 1, 1}).rank_biserial, 1.0);
}

TEST(WilcoxonSignedRankTest, ZeroDifferencesAreDropped) {
  EXPECT_EQ(WilcoxonSignedRank({1, 2, 3, 4}, {1, 2, 0, 0}).n, 2);
}

// Ties among |d| (1, 1, 2): the normal approximation. Ranks 1.5, 1.5, 3 all positive:
// W+ = 6, mean 3, variance 3·4·7/24 − 6/48 = 3.375; z = (3 − 0.5) / sqrt(3.375) = 1.36083,
// p = erfc(z / √2) = 0.173567.
TEST(WilcoxonSignedRankTest, TiedMagnitudesUseCorrectedNormalApproximation) {
  const WilcoxonResult r = WilcoxonSignedRank({2, 2, 3}, {1, 1, 1});
  EXPECT_FALSE(r.exact);
  EXPECT_NEAR(r.p_value, std::erfc(2.5 / std::sqrt(3.375) / std::sqrt(2.0)), 1e-12);
}

TEST(WilcoxonSignedRankTest, DifferentLengthsAreRefused) {
  EXPECT_THROW(WilcoxonSignedRank({1, 2}, {1}), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
