#include "common/search/subpixel.hpp"

#include <gtest/gtest.h>

#include "common/search/match_confidence.hpp"

namespace kapfix {
namespace {

TEST(SubpixelTest, VertexOfASymmetricParabolaIsTheCentre) {
  EXPECT_DOUBLE_EQ(ParabolaVertexOffset(10, 1, 10), 0.0);
}

TEST(SubpixelTest, VertexOfASampledParabolaIsExact) {
  // d(s) = (s − 0.3)²·100 sampled at −1, 0, 1.
  auto d = [](double s) { return static_cast<std::int64_t>((s - 0.3) * (s - 0.3) * 100 + 0.5); };
  EXPECT_NEAR(ParabolaVertexOffset(d(-1), d(0), d(1)), 0.3, 0.01);
}

TEST(SubpixelTest, NoOffsetWhenTheCentreIsNotTheLowest) {
  EXPECT_DOUBLE_EQ(ParabolaVertexOffset(1, 5, 9), 0.0);
}

TEST(MatchConfidenceTest, ASecondEqualValleyMeansZeroConfidence) {
  const std::map<int, std::int64_t> curve{{-4, 50}, {-3, 10}, {-2, 50}, {0, 80},
                                          {2, 50},  {3, 10},  {4, 50}};
  EXPECT_DOUBLE_EQ(MatchConfidence(curve), 0.0);
}

TEST(MatchConfidenceTest, ASingleBasinIsComparedWithItsHighestPoint) {
  const std::map<int, std::int64_t> curve{{-3, 100}, {-2, 60}, {-1, 30}, {0, 10},
                                          {1, 30},   {2, 60},  {3, 100}};
  EXPECT_DOUBLE_EQ(MatchConfidence(curve), 0.9);
}

TEST(MatchConfidenceTest, AShallowerRivalGivesPartialConfidence) {
  // best 20, rival 40, highest 90: min(1 − 20/40, (40 − 20)/(90 − 20)) = 2/7.
  const std::map<int, std::int64_t> curve{{-6, 90}, {-5, 40}, {-4, 90}, {0, 90}, {1, 20}, {2, 90}};
  EXPECT_DOUBLE_EQ(MatchConfidence(curve), 2.0 / 7.0);
}

TEST(MatchConfidenceTest, ARivalNearlyAsGoodAsTheBestIsAmbiguousWhateverTheFloor) {
  // A repetitive texture's valleys one period apart, under a rise far larger than their
  // difference: the ratio alone (1 − 1000/1050 ≈ 0.05… or 0.5 for best 50, rival 100) would
  // call it locked; the share of the rise (50/950) says it is not.
  const std::map<int, std::int64_t> curve{{-12, 1000}, {-10, 100}, {-8, 1000},
                                          {0, 1000},   {2, 50},    {4, 1000}};
  EXPECT_NEAR(MatchConfidence(curve), 50.0 / 950.0, 1e-12);
  // The same valleys raised by a common noise floor keep the same share.
  std::map<int, std::int64_t> floored;
  for (const auto& [shift, d] : curve) floored[shift] = d + 5000;
  EXPECT_LE(MatchConfidence(floored), 50.0 / 950.0 + 1e-12);
}

TEST(MatchConfidenceTest, APairListInPositionOrderReadsLikeTheMap) {
  const std::vector<std::pair<int, std::int64_t>> curve{{-6, 90}, {-5, 40}, {-4, 90},
                                                        {0, 90},  {1, 20},  {2, 90}};
  EXPECT_DOUBLE_EQ(MatchConfidence(curve), 2.0 / 7.0);
  EXPECT_DOUBLE_EQ(MatchConfidence(curve, 6), 1.0 - 20.0 / 90.0);  // rival excluded: highest
  EXPECT_DOUBLE_EQ(MatchConfidence(std::vector<std::pair<int, std::int64_t>>{{0, 5}}), 0.0);
}

}  // namespace
}  // namespace kapfix
