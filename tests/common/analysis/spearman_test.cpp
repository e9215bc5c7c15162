#include "common/analysis/spearman.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace kapfix {
namespace {

TEST(SpearmanTest, MonotoneIncreasingIsOne) {
  // Not linear: only the order counts.
  EXPECT_DOUBLE_EQ(SpearmanCorrelation({1, 2, 3, 4, 5}, {1, 8, 27, 64, 125}), 1.0);
}

TEST(SpearmanTest, ReversedOrderIsMinusOne) {
  EXPECT_DOUBLE_EQ(SpearmanCorrelation({1, 2, 3, 4}, {9, 7, 3, 0}), -1.0);
}

TEST(SpearmanTest, HandExampleWithoutTies) {
  // Rank differences −1, 1, −1, 1, 0: Σd² = 4, ρ = 1 − 6 · 4 / (5 · 24) = 0.8.
  EXPECT_NEAR(SpearmanCorrelation({1, 2, 3, 4, 5}, {2, 1, 4, 3, 5}), 0.8, 1e-12);
}

TEST(SpearmanTest, TiesUsePearsonOnAverageRanks) {
  // Ranks (1, 2, 3, 4) and (1, 2.5, 2.5, 4), both centred on 2.5: Σ products 4.5, Σ squares 5
  // and 4.5, ρ = 4.5 / sqrt(22.5) = sqrt(0.9). The Σd² shortcut would say 0.95.
  EXPECT_NEAR(SpearmanCorrelation({1, 2, 3, 4}, {1, 2, 2, 3}), std::sqrt(0.9), 1e-12);
}

TEST(SpearmanTest, RejectsDifferentLengths) {
  EXPECT_THROW(SpearmanCorrelation({1, 2, 3}, {1, 2}), std::invalid_argument);
}

TEST(SpearmanTest, RejectsAConstantSequence) {
  EXPECT_THROW(SpearmanCorrelation({1, 2, 3}, {5, 5, 5}), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix

namespace kapfix {
namespace {

// n = 5, b swaps the first two ranks: Σd² = 2, ρ = 1 − 6·2 / 120 = 0.9. Orderings with
// Σd² ≤ 2 are the identity and the 4 adjacent swaps; with their reversals 10 of 120 reach
// |ρ| ≥ 0.9: exact two-sided p = 1/12 (published tables: n = 5 needs ρ = 1 for p < 0.05).
TEST(SpearmanTestTest, SmallSampleGivesExactPermutationPValue) {
  const SpearmanResult r = SpearmanTest({1, 2, 3, 4, 5}, {2, 1, 3, 4, 5});
  EXPECT_TRUE(r.exact);
  EXPECT_NEAR(r.rho, 0.9, 1e-12);
  EXPECT_NEAR(r.p_value, 10.0 / 120.0, 1e-12);
}

// Ties in b (two 7s share rank 3.5): the permutation keeps the tie.
TEST(SpearmanTestTest, TiesKeepTheirAverageRanksInThePermutation) {
  const SpearmanResult r = SpearmanTest({1, 2, 3, 4}, {1, 2, 7, 7});
  EXPECT_TRUE(r.exact);
  // Distinct orderings of ranks {1, 2, 3.5, 3.5}: 12. |ρ| is largest (0.9487) for the sorted
  // one and its reversal: p = 2 / 12.
  EXPECT_NEAR(r.p_value, 2.0 / 12.0, 1e-12);
}

TEST(SpearmanTestTest, LargeSampleUsesTheTApproximation) {
  std::vector<double> a;
  std::vector<double> b;
  for (int i = 0; i < 12; ++i) {
    a.push_back(i);
    b.push_back(i + ((i % 3 == 0) ? 2.5 : 0.0));
  }
  const SpearmanResult r = SpearmanTest(a, b);
  EXPECT_FALSE(r.exact);
  EXPECT_LT(r.p_value, 0.001);
}

}  // namespace
}  // namespace kapfix
