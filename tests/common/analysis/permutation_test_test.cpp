#include "common/analysis/permutation_test.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace kapfix {
namespace {

// One group of 5 in perfect order: ρ = 1, reached (in absolute value) by 2 of the 120
// orderings, so the permutation p tends to 2/120 = 0.0167; 20,000 draws land within ±0.004.
TEST(PermutationTestTest, OneOrderedGroupApproachesExactShare) {
  const auto r = PooledSpearmanPermutationTest({{1, 2, 3, 4, 5}}, {{10, 20, 30, 40, 50}}, 20000, 7);
  EXPECT_DOUBLE_EQ(r.mean_rho, 1.0);
  EXPECT_NEAR(r.p_value, 2.0 / 120.0, 0.004);
}

// Three images each ordered perfectly: mean ρ = 1 only when all three permutations are the
// identity or reversal in step, (2/120)·(1/120)² ≈ 1e-6: p is the floor 1 / (1 + M).
TEST(PermutationTestTest, PoolingImagesSharpensTheTest) {
  const std::vector<std::vector<double>> s = {{1, 2, 3, 4, 5}, {5, 1, 2, 3, 4}, {2, 1, 3, 5, 4}};
  const auto r = PooledSpearmanPermutationTest(s, s, 2000, 1);
  EXPECT_DOUBLE_EQ(r.p_value, 1.0 / 2001.0);
  EXPECT_EQ(r.groups_used, 3);
}

TEST(PermutationTestTest, ConstantGroupIsLeftOut) {
  const auto r =
      PooledSpearmanPermutationTest({{1, 2, 3}, {1, 2, 3}}, {{1, 2, 3}, {4, 4, 4}}, 100, 1);
  EXPECT_EQ(r.groups_used, 1);
}

TEST(PermutationTestTest, MismatchedGroupIsRefused) {
  EXPECT_THROW(PooledSpearmanPermutationTest({{1, 2, 3}}, {{1, 2}}, 100, 1), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
