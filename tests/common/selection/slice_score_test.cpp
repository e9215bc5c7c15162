#include "common/selection/slice_score.hpp"

#include <gtest/gtest.h>

namespace kapfix {
namespace {

SliceScore Score(int index, int dc, double fft, int dc_hysteresis = 0, double single_shot = 0.0) {
  SliceScore s;
  s.index = index;
  s.dc = dc;
  s.fft = fft;
  s.dc_hysteresis = dc_hysteresis;
  s.single_shot = single_shot;
  return s;
}

TEST(SliceScoreKindTest, ParsesWhatItPrints) {
  for (const SliceScoreKind kind : {SliceScoreKind::kDc, SliceScoreKind::kDcHysteresis,
                                    SliceScoreKind::kFft, SliceScoreKind::kSingleShot}) {
    EXPECT_EQ(ParseSliceScoreKind(ToString(kind)), kind);
  }
  EXPECT_EQ(ToString(SliceScoreKind::kDcHysteresis), "dc-hyst");
  EXPECT_EQ(ToString(SliceScoreKind::kSingleShot), "single-shot");
}

TEST(SliceScoreKindTest, RefusesAnUnknownName) {
  EXPECT_FALSE(ParseSliceScoreKind("dcs").has_value());
}

TEST(RankSlicesTest, AmbiguousSlicesComeAfterEveryUnambiguousOne) {
  std::vector<SliceScore> scores{Score(1, 30, 1.0), Score(2, 10, 9.0), Score(3, 20, 5.0)};
  scores[1].ambiguous = true;  // the fewest direction changes, but a repetitive texture
  EXPECT_EQ(RankSlices(scores, SliceScoreKind::kDc), (std::vector<int>{3, 1, 2}));
}

TEST(RankSlicesTest, DcRanksFewestChangesFirst) {
  const std::vector<SliceScore> scores{Score(1, 30, 1.0), Score(2, 10, 9.0), Score(3, 20, 5.0)};
  EXPECT_EQ(RankSlices(scores, SliceScoreKind::kDc), (std::vector<int>{2, 3, 1}));
}

TEST(RankSlicesTest, DcHysteresisRanksFewestChangesFirst) {
  const std::vector<SliceScore> scores{Score(1, 1, 1.0, 7), Score(2, 2, 1.0, 3),
                                       Score(3, 3, 1.0, 5)};
  EXPECT_EQ(RankSlices(scores, SliceScoreKind::kDcHysteresis), (std::vector<int>{2, 3, 1}));
}

TEST(RankSlicesTest, FftRanksLowestScoreFirst) {
  const std::vector<SliceScore> scores{Score(1, 1, 30.0), Score(2, 2, 10.0), Score(3, 3, 20.0)};
  EXPECT_EQ(RankSlices(scores, SliceScoreKind::kFft), (std::vector<int>{2, 3, 1}));
}

TEST(RankSlicesTest, SingleShotRanksHighestScoreFirst) {
  const std::vector<SliceScore> scores{Score(1, 1, 1.0, 0, 0.2), Score(2, 2, 2.0, 0, 0.9),
                                       Score(3, 3, 3.0, 0, 0.5)};
  EXPECT_EQ(RankSlices(scores, SliceScoreKind::kSingleShot), (std::vector<int>{2, 3, 1}));
}

TEST(RankSlicesTest, EqualDcIsBrokenByTheLowerFft) {
  const std::vector<SliceScore> scores{Score(4, 10, 8.0), Score(5, 10, 9.0), Score(6, 10, 7.0)};
  EXPECT_EQ(RankSlices(scores, SliceScoreKind::kDc, 9), (std::vector<int>{6, 4, 5}));
}

TEST(RankSlicesTest, EqualSingleShotIsBrokenByTheLowerFft) {
  const std::vector<SliceScore> scores{Score(4, 1, 8.0, 0, 0.5), Score(5, 1, 7.0, 0, 0.5)};
  EXPECT_EQ(RankSlices(scores, SliceScoreKind::kSingleShot, 9), (std::vector<int>{5, 4}));
}

TEST(RankSlicesTest, EqualDcAndFftAreBrokenByClosenessToTheCentre) {
  const std::vector<SliceScore> scores{Score(1, 10, 5.0), Score(8, 10, 5.0), Score(4, 10, 5.0),
                                       Score(5, 12, 1.0)};
  EXPECT_EQ(RankSlices(scores, SliceScoreKind::kDc, 9), (std::vector<int>{4, 8, 1, 5}));
}

TEST(RankSlicesTest, SlicesEquallyFarFromTheCentreRankTheUpperFirst) {
  const std::vector<SliceScore> scores{Score(6, 10, 5.0), Score(4, 10, 5.0)};
  EXPECT_EQ(RankSlices(scores, SliceScoreKind::kDc, 9), (std::vector<int>{4, 6}));
}

TEST(RankSlicesTest, CentreIsTakenFromTheLargestIndexWithoutASliceCount) {
  const std::vector<SliceScore> scores{Score(1, 10, 5.0), Score(2, 10, 5.0), Score(3, 10, 5.0)};
  EXPECT_EQ(RankSlices(scores, SliceScoreKind::kDc).front(), 2);
  EXPECT_EQ(RankSlices(scores, SliceScoreKind::kDc, 9).front(), 3);
}

}  // namespace
}  // namespace kapfix
