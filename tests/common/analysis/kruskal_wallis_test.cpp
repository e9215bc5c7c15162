#include "common/analysis/kruskal_wallis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace kapfix {
namespace {

// Textbook example, no ties. Pooled ranks 1…14 give rank sums 36 (n 5), 36 (n 4), 33 (n 5):
// Σ R²/n = 259.2 + 324 + 217.8 = 801, H = 12 / (14 · 15) · 801 − 3 · 15 = 0.771429.
// With 2 dof the χ² upper tail is exp(−H / 2) = 0.679965 (also python3: math.exp(-H/2)).
const std::vector<std::vector<double>> kTextbook = {
    {2.9, 3.0, 2.5, 2.6, 3.2}, {3.8, 2.7, 4.0, 2.4}, {2.8, 3.4, 3.7, 2.2, 2.0}};

TEST(KruskalWallisTest, TextbookExampleGivesH) {
  EXPECT_NEAR(KruskalWallis(kTextbook).h, 0.7714285714, 1e-9);
}

TEST(KruskalWallisTest, TextbookExampleGivesPValueFromChiSquare) {
  EXPECT_NEAR(KruskalWallis(kTextbook).p_value, std::exp(-0.7714285714285714 / 2), 1e-9);
}

TEST(KruskalWallisTest, DegreesOfFreedomAreGroupsMinusOne) {
  EXPECT_EQ(KruskalWallis(kTextbook).degrees_of_freedom, 2);
}

TEST(KruskalWallisTest, WithoutTiesTheCorrectionChangesNothing) {
  const KruskalWallisResult r = KruskalWallis(kTextbook);
  EXPECT_DOUBLE_EQ(r.h_corrected, r.h);
}

// Tied example by hand: A = {1, 2, 2}, B = {2, 3, 3}, N = 6. Sorted 1 | 2 2 2 | 3 3 get ranks
// 1 | 3 3 3 | 5.5 5.5, so R_A = 7, R_B = 14 and H = 12 / 42 · (49 + 196) / 3 − 21 = 7/3.
// Ties: a triple and a pair, Σ(t³ − t) = 24 + 6 = 30, correction 1 − 30 / 210 = 6/7,
// H_c = 49/18 = 2.7222. One dof: p = P(χ²₁ > H_c) = erfc(sqrt(H_c / 2)) = erfc(7/6) = 0.09896.
const std::vector<std::vector<double>> kTied = {{1, 2, 2}, {2, 3, 3}};

TEST(KruskalWallisTest, TiedExampleGivesUncorrectedH) {
  EXPECT_NEAR(KruskalWallis(kTied).h, 7.0 / 3.0, 1e-12);
}

TEST(KruskalWallisTest, TieCorrectionDividesHByOneMinusTieShare) {
  EXPECT_NEAR(KruskalWallis(kTied).h_corrected, 49.0 / 18.0, 1e-12);
}

TEST(KruskalWallisTest, PValueUsesTheCorrectedH) {
  EXPECT_NEAR(KruskalWallis(kTied).p_value, std::erfc(7.0 / 6.0), 1e-12);
}

TEST(KruskalWallisTest, SeparatedGroupsGiveASmallPValue) {
  EXPECT_LT(KruskalWallis({{1, 2, 3, 4, 5}, {11, 12, 13, 14, 15}}).p_value, 0.01);
}

TEST(KruskalWallisTest, AllValuesEqualMeansNoEvidence) {
  const KruskalWallisResult r = KruskalWallis({{4, 4}, {4, 4, 4}});
  EXPECT_EQ(r.h_corrected, 0.0);
  EXPECT_EQ(r.p_value, 1.0);
}

TEST(KruskalWallisTest, RejectsFewerThanTwoGroups) {
  EXPECT_THROW(KruskalWallis({{1, 2, 3}}), std::invalid_argument);
}

TEST(KruskalWallisTest, RejectsAnEmptyGroup) {
  EXPECT_THROW(KruskalWallis({{1, 2}, {}}), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
