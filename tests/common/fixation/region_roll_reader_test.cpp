#include "common/fixation/region_roll_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>

#include "common/fixation/patch_roll.hpp"
#include "common/image/color_channel.hpp"
#include "common/matching/reference_patch.hpp"
#include "common/search/search_strategy.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180;
const cv::Size kFrame{640, 480};
const cv::Rect kCentrePatch{270, 190, 100, 100};  // slice 5 of 9: on the frame centre

// A photo through a kFrame-sized view, rolled by `roll_deg` about the view's centre and
// shifted by `shift` [px], enlarged by `scale` first; the green plane, as the loop reads it.
cv::Mat View(const std::string& photo, double roll_deg, cv::Point2d shift, double scale = 1) {
  return ExtractChannel(testing::RolledView(photo, kFrame, roll_deg, shift, scale),
                        ColorChannel::kGreen);
}

class RegionRollReaderTest : public ::testing::TestWithParam<double> {};

TEST_P(RegionRollReaderTest, ReadsTheRollAndShiftOfAFrameTurnedAboutItsCentre) {
  const cv::Point2d shift(5, -3);
  const RegionRollReader reader(View("aero1.jpg", 0, {0, 0}), kCentrePatch, {});
  // Started 2° off, from a displacement 4 px off.
  const std::optional<RegionRoll> read =
      reader.Read(View("aero1.jpg", GetParam(), shift), shift + cv::Point2d(4, -2), GetParam() - 2);
  ASSERT_TRUE(read.has_value());
  EXPECT_NEAR(read->roll_deg, GetParam(), 0.2);
  EXPECT_NEAR(read->displacement.x, shift.x, 0.5);
  EXPECT_NEAR(read->displacement.y, shift.y, 0.5);
  EXPECT_GT(read->correlation, 0.9);
}

INSTANTIATE_TEST_SUITE_P(Rolls, RegionRollReaderTest,
                         ::testing::Values(-12.0, -2.0, 0.0, 3.0, 8.0));

// smarties.png as the simulator shows it (enlarged 2.18×): the centre patch is dominated by
// sweets ~70 px above its centre, so the upright patch's best shift under a roll θ is ~70·θ
// sideways, and the patch read at that shift is level. The region around it is not fooled.
TEST(RegionRollReaderTest, ReadsARollThatThePatchAloneTakesForAShift) {
  constexpr double kScale = 2.18, kRoll = 8;
  const cv::Mat reference = View("smarties.png", 0, {0, 0}, kScale);
  const cv::Mat rolled = View("smarties.png", kRoll, {0, 0}, kScale);
  std::string error;
  const auto pyr = MakeSearchStrategy("pyr", &error);
  SearchOptions search;
  search.axis = SearchAxis::kBoth;
  const SearchResult upright = pyr->Search(
      ReferencePatch(reference, SampleSet({kCentrePatch}, SamplingOptions{})), rolled, search);
  ASSERT_TRUE(upright.found);
  ASSERT_GT(std::abs(upright.displacement.x), 5) << "the upright patch slides sideways";
  const std::optional<PatchRoll> patch_read =
      ReadPatchRoll(reference, kCentrePatch, rolled, upright.displacement, {});
  ASSERT_TRUE(patch_read.has_value());
  ASSERT_LT(std::abs(patch_read->roll_rad / kRadPerDeg), 2) << "read at that shift: nearly level";

  const RegionRollReader reader(reference, kCentrePatch, {});
  // From level, at the upright search's displacement.
  const std::optional<RegionRoll> read = reader.Read(rolled, upright.displacement, 0);
  ASSERT_TRUE(read.has_value());
  EXPECT_NEAR(read->roll_deg, kRoll, 0.4);
  EXPECT_LT(std::hypot(read->displacement.x, read->displacement.y), 1);
}

// Another photo where the region should be: nothing is read, rather than a roll.
TEST(RegionRollReaderTest, AFrameThatDoesNotShowTheRegionIsNotRead) {
  const RegionRollReader reader(View("aero1.jpg", 0, {0, 0}), kCentrePatch, {});
  EXPECT_FALSE(reader.Read(View("fruits.jpg", 0, {0, 0}), {0, 0}, 0).has_value());
}

// The alignment's correlation is blind to brightness: an auto-exposure step is no roll.
TEST(RegionRollReaderTest, ABrighterFrameReadsTheSameRoll) {
  const RegionRollReader reader(View("aero1.jpg", 0, {0, 0}), kCentrePatch, {});
  cv::Mat brighter;
  View("aero1.jpg", 4, {0, 0}).convertTo(brighter, -1, 1.2, 0);
  const std::optional<RegionRoll> read = reader.Read(brighter, {0, 0}, 0);
  ASSERT_TRUE(read.has_value());
  EXPECT_NEAR(read->roll_deg, 4, 0.2);
}

// Frames whose height is not a multiple of the reduction keep the reduced grid exact (shrunk
// to a size that is not 1/4 of theirs, the pixels spread and the content moves).
TEST(RegionRollReaderTest, AFrameNotAMultipleOfTheReductionIsReadWithoutBias) {
  const cv::Mat photo = ExtractChannel(testing::LoadOpenCvPhoto("aero1.jpg"), ColorChannel::kGreen);
  const cv::Mat frame = photo(cv::Rect(100, 100, 400, 300)).clone();
  const RegionRollReader reader(frame, {150, 100, 100, 100}, {});
  const std::optional<RegionRoll> read = reader.Read(frame, {0, 0}, 0);
  ASSERT_TRUE(read.has_value());
  EXPECT_NEAR(read->roll_deg, 0, 0.1);
  EXPECT_NEAR(read->displacement.y, 0, 0.5);
}

TEST(RegionRollReaderTest, ARegionDisplacedOutOfTheFrameIsNotRead) {
  const cv::Mat frame = View("aero1.jpg", 0, {0, 0});
  const RegionRollReader reader(frame, kCentrePatch, {});
  EXPECT_FALSE(reader.Read(frame, {300, 0}, 0).has_value());
}

// SSP may choose the bottom slice, whose patch touches the frame's edge: the region reaches
// away from the edge instead.
TEST(RegionRollReaderTest, ReadsTheRollAroundAPatchOnTheFramesEdge) {
  const cv::Rect bottom(270, 380, 100, 100);
  const RegionRollReader reader(View("aero1.jpg", 0, {0, 0}), bottom, {});
  // The patch centre is 190 px below the frame centre: a roll of 4° moves it 13 px sideways.
  const cv::Point2d moved(-190 * std::sin(4 * kRadPerDeg), 190 * (std::cos(4 * kRadPerDeg) - 1));
  const std::optional<RegionRoll> read = reader.Read(View("aero1.jpg", 4, {0, 0}), moved, 3);
  ASSERT_TRUE(read.has_value());
  EXPECT_NEAR(read->roll_deg, 4, 0.2);
  EXPECT_NEAR(read->displacement.x, moved.x, 0.5);
}

TEST(RegionRollReaderTest, APatchAsLargeAsTheFrameLeavesNoRegionToRead) {
  const cv::Mat frame = View("aero1.jpg", 0, {0, 0});
  const RegionRollReader reader(frame, {80, 0, 480, 480}, {});
  EXPECT_FALSE(reader.Read(frame, {0, 0}, 0).has_value());
}

TEST(RegionRollReaderTest, ADefaultReaderReadsNothing) {
  EXPECT_FALSE(RegionRollReader().Read(View("aero1.jpg", 0, {0, 0}), {0, 0}, 0).has_value());
}

TEST(RegionRollOptionsTest, RejectsACorrelationOfOne) {
  RegionRollOptions o;
  o.min_correlation = 1;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("correlation"), std::string::npos) << error;
}

TEST(RegionRollOptionsTest, RejectsNoIteration) {
  RegionRollOptions o;
  o.iterations = 0;
  EXPECT_FALSE(o.IsValid(nullptr));
  EXPECT_TRUE(RegionRollOptions{}.IsValid(nullptr));
}

}  // namespace
}  // namespace kapfix
