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
  const std::map<int, std::int64_t> curve{{-6, 90}, {-5, 40}, {-4, 90}, {0, 90}, {1, 20}, {2, 90}};
  EXPECT_DOUBLE_EQ(MatchConfidence(curve), 0.5);
}

TEST(MatchConfidenceTest, APairListInPositionOrderReadsLikeTheMap) {
  const std::vector<std::pair<int, std::int64_t>> curve{{-6, 90}, {-5, 40}, {-4, 90},
                                                        {0, 90},  {1, 20},  {2, 90}};
  EXPECT_DOUBLE_EQ(MatchConfidence(curve), 0.5);
  EXPECT_DOUBLE_EQ(MatchConfidence(curve, 6), 1.0 - 20.0 / 90.0);  // rival excluded: highest
  EXPECT_DOUBLE_EQ(MatchConfidence(std::vector<std::pair<int, std::int64_t>>{{0, 5}}), 0.0);
}

}  // namespace
}  // namespace kapfix
