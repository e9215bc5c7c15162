#include "common/analysis/spearman.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

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
