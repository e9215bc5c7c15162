#include "common/selection/single_shot_score.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

// A hand-made self-comparison curve over shifts first, first + 1, ….
ErrorCurve Curve(int first, std::vector<std::int64_t> distances) {
  ErrorCurve curve;
  for (int i = 0; i < static_cast<int>(distances.size()); ++i) curve.shifts.push_back(first + i);
  curve.distances = std::move(distances);
  return curve;
}

const cv::Rect kCentralPatch(100, 100, 100, 100);

SearchOptions AlongX() {
  SearchOptions options;
  options.axis = SearchAxis::kX;
  return options;
}

// Vertical stripes of period `period` [px]: every shift by a multiple of it matches exactly.
cv::Mat Stripes(cv::Size size, int period) {
  cv::Mat image(size, CV_8UC1);
  for (int x = 0; x < size.width; ++x) {
    const double v = 128.0 + 100.0 * std::sin(2.0 * std::numbers::pi * x / period);
    image.col(x).setTo(cv::Scalar(std::round(v)));
  }
  return image;
}

TEST(SingleShotScoreTest, ACleanBasinIsFullyDistinct) {
  std::vector<std::int64_t> d;
  for (int s = -10; s <= 10; ++s) d.push_back(10 * std::abs(s));
  const SingleShotScore score = SingleShotScoreFromCurve(Curve(-10, d));
  EXPECT_DOUBLE_EQ(score.distinctness, 1.0);
  EXPECT_DOUBLE_EQ(score.basin_width_px, 10.0);
}

TEST(SingleShotScoreTest, ASecondZeroValleyMeansNoDistinctness) {
  const SingleShotScore score = SingleShotScoreFromCurve(
      Curve(-8, {80, 70, 60, 50, 40, 30, 20, 10, 0, 10, 20, 30, 20, 10, 0, 10, 20}));
  EXPECT_DOUBLE_EQ(score.distinctness, 0.0);
  EXPECT_DOUBLE_EQ(score.score, 0.0);
}

TEST(SingleShotScoreTest, AMinimumWithinTwoPixelsOfTheSelfMatchIsNoRival) {
  // The dip to 5 at shift +2 belongs to the global basin; the rival falls back to the highest
  // distance (50), which is above the median (20).
  const SingleShotScore score =
      SingleShotScoreFromCurve(Curve(-5, {50, 40, 30, 20, 10, 0, 10, 5, 20, 30, 40}));
  EXPECT_DOUBLE_EQ(score.distinctness, 1.0);
}

TEST(SingleShotScoreTest, AnEndOfTheCurveLowerThanItsNeighbourIsARival) {
  // Rival 10 at shift −4, median 20.
  const SingleShotScore score =
      SingleShotScoreFromCurve(Curve(-4, {10, 30, 20, 10, 0, 10, 20, 30, 40}));
  EXPECT_DOUBLE_EQ(score.distinctness, 0.5);
}

TEST(SingleShotScoreTest, AFlatValleyFloorIsARival) {
  // Rival 5 on the plateau at shifts +3, +4; median 20.
  const SingleShotScore score =
      SingleShotScoreFromCurve(Curve(-6, {60, 50, 40, 30, 20, 10, 0, 10, 20, 5, 5, 20, 30}));
  EXPECT_DOUBLE_EQ(score.distinctness, 0.25);
}

TEST(SingleShotScoreTest, BasinWidthIsTheMeanRiseOnBothSides) {
  // Left: rises to shift −4 (4 px); right: rises to +2 (2 px), then falls.
  const SingleShotScore score =
      SingleShotScoreFromCurve(Curve(-6, {5, 6, 40, 30, 20, 10, 0, 10, 20, 15, 30, 45, 50}));
  EXPECT_DOUBLE_EQ(score.basin_width_px, 3.0);
}

TEST(SingleShotScoreTest, ScoreIsDistinctnessTimesTheBasinFactor) {
  // Distinctness 0.5; basin 3 px left, 4 px right.
  const SingleShotScore score =
      SingleShotScoreFromCurve(Curve(-4, {10, 30, 20, 10, 0, 10, 20, 30, 40}));
  EXPECT_DOUBLE_EQ(score.basin_width_px, 3.5);
  EXPECT_DOUBLE_EQ(score.score, 0.5 * (1.0 - std::exp(-3.5 / 8.0)));
}

TEST(SingleShotScoreTest, ACurveWithoutTheSelfMatchScoresZero) {
  const SingleShotScore score = SingleShotScoreFromCurve(Curve(3, {0, 10, 20, 30}));
  EXPECT_EQ(score.score, 0.0);
  EXPECT_EQ(score.distinctness, 0.0);
}

TEST(SingleShotScoreTest, RepetitiveStripesScoreBelowASmoothTexture) {
  const cv::Mat stripes = Stripes({300, 300}, 12);
  const cv::Mat texture = testing::SmoothTexture({300, 300}, 11);
  const SingleShotScore repetitive = ComputeSingleShotScore(stripes, kCentralPatch, {}, AlongX());
  const SingleShotScore smooth = ComputeSingleShotScore(texture, kCentralPatch, {}, AlongX());
  EXPECT_LT(repetitive.score, 0.05);
  EXPECT_GT(smooth.score, 0.3);
}

TEST(SingleShotScoreTest, RepetitiveStripesAreMarkedAmbiguousASmoothTextureIsNot) {
  const cv::Mat stripes = Stripes({300, 300}, 12);
  const cv::Mat texture = testing::SmoothTexture({300, 300}, 11);
  EXPECT_TRUE(ComputeSingleShotScore(stripes, kCentralPatch, {}, AlongX()).ambiguous);
  EXPECT_FALSE(ComputeSingleShotScore(texture, kCentralPatch, {}, AlongX()).ambiguous);
}

TEST(SingleShotScoreTest, TheChessboardIsMarkedAmbiguous) {
  cv::Mat grey;
  cv::cvtColor(testing::LoadOpenCvPhoto("left01.jpg"), grey, cv::COLOR_BGR2GRAY);
  // The board fills the middle of the photo: a 100 px patch there, searched ±100 px.
  SearchOptions search = AlongX();
  search.range = 100;
  EXPECT_TRUE(ComputeSingleShotScore(grey, cv::Rect(270, 190, 100, 100), {}, search).ambiguous);
}

TEST(SingleShotScoreTest, AFlatPatchScoresZero) {
  const cv::Mat flat(300, 300, CV_8UC1, cv::Scalar(128));
  EXPECT_EQ(ComputeSingleShotScore(flat, kCentralPatch, {}, AlongX()).score, 0.0);
}

TEST(SingleShotScoreTest, BothAxesKeepTheWeakerAxis) {
  // Texture along x only: every row is the same, so the Y curve is flat.
  const cv::Mat row = testing::SmoothTexture({300, 1}, 12, 2.0);
  cv::Mat columns;
  cv::repeat(row, 300, 1, columns);
  SearchOptions both = AlongX();
  both.axis = SearchAxis::kBoth;
  EXPECT_GT(ComputeSingleShotScore(columns, kCentralPatch, {}, AlongX()).score, 0.3);
  EXPECT_EQ(ComputeSingleShotScore(columns, kCentralPatch, {}, both).score, 0.0);
}

TEST(SingleShotScoreTest, RefusesAPatchOutsideThePlane) {
  const cv::Mat texture = testing::SmoothTexture({300, 300}, 13);
  EXPECT_THROW(ComputeSingleShotScore(texture, cv::Rect(250, 0, 100, 100), {}, AlongX()),
               std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
