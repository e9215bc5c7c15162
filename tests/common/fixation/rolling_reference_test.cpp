#include "common/fixation/rolling_reference.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/image/color_channel.hpp"
#include "common/search/search_strategy.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

const cv::Size kFrame{640, 480};
const cv::Rect kCentrePatch{270, 190, 100, 100};

cv::Mat View(const std::string& photo, double roll_deg, double scale = 1) {
  return ExtractChannel(testing::RolledView(photo, kFrame, roll_deg, {0, 0}, scale),
                        ColorChannel::kGreen);
}

RollingReference Stored(const cv::Mat& plane, RollTrackingOptions options = {}) {
  RollingReference reference(options);
  reference.Reset(plane, kCentrePatch, SampleSet({kCentrePatch}, SamplingOptions{}));
  return reference;
}

SearchResult Search(const ReferencePatch& reference, const cv::Mat& plane) {
  std::string error;
  SearchOptions search;
  search.axis = SearchAxis::kBoth;
  return MakeSearchStrategy("pyr", &error)->Search(reference, plane, search);
}

TEST(RollingReferenceTest, ARollWithinTheDeadBandLeavesTheReferenceUpright) {
  RollingReference reference = Stored(View("aero1.jpg", 0));
  const cv::Mat rolled = View("aero1.jpg", 1);
  for (int frame = 0; frame < 10; ++frame) ASSERT_TRUE(reference.Track(rolled, {0, 0}));
  EXPECT_NEAR(reference.estimate_deg(), 1, 0.3);
  EXPECT_EQ(reference.turn_deg(), 0);
  EXPECT_EQ(&reference.reference(), &reference.stored());
}

TEST(RollingReferenceTest, ARollPastTheDeadBandTurnsTheReferenceInWholeSteps) {
  RollingReference reference = Stored(View("aero1.jpg", 0));
  const cv::Mat rolled = View("aero1.jpg", 4.2);
  for (int frame = 0; frame < 12; ++frame) reference.Track(rolled, {0, 0});
  EXPECT_NEAR(reference.estimate_deg(), 4.2, 0.3);
  EXPECT_EQ(reference.turn_deg(), 4);
  EXPECT_NE(&reference.reference(), &reference.stored());
  EXPECT_GT(cv::norm(reference.reference().image(), reference.stored().image(), cv::NORM_L1), 0);
}

// smarties.png as the simulator shows it: the upright patch answers a roll with a sideways
// shift of ~70 px per radian; the reference turned by the roll tracked frame by frame is found
// where the view is.
TEST(RollingReferenceTest, TheTurnedReferenceIsFoundWhereTheUprightOneSlidesAway) {
  constexpr double kScale = 2.18;
  RollingReference reference = Stored(View("smarties.png", 0, kScale));
  cv::Mat frame;
  for (double roll = 0.5; roll <= 8; roll += 0.5) {  // a camera rolling 0.5° a frame
    frame = View("smarties.png", roll, kScale);
    const SearchResult match = Search(reference.reference(), frame);
    ASSERT_TRUE(match.found) << roll;
    reference.Track(frame, match.displacement);
  }
  EXPECT_NEAR(reference.estimate_deg(), 8, 1);
  const SearchResult upright = Search(reference.stored(), frame);
  const SearchResult turned = Search(reference.reference(), frame);
  EXPECT_GT(std::hypot(upright.displacement.x, upright.displacement.y), 5);
  EXPECT_LT(std::hypot(turned.displacement.x, turned.displacement.y), 1.5);
}

TEST(RollingReferenceTest, ANewReferenceForgetsTheRoll) {
  RollingReference reference = Stored(View("aero1.jpg", 0));
  const cv::Mat rolled = View("aero1.jpg", 5);
  for (int frame = 0; frame < 12; ++frame) reference.Track(rolled, {0, 0});
  ASSERT_NE(reference.turn_deg(), 0);
  reference.Reset(rolled, kCentrePatch, SampleSet({kCentrePatch}, SamplingOptions{}));
  EXPECT_EQ(reference.estimate_deg(), 0);
  EXPECT_EQ(reference.turn_deg(), 0);
  EXPECT_EQ(&reference.reference(), &reference.stored());
}

TEST(RollingReferenceTest, TrackingOffReadsNothingAndNeverTurns) {
  RollTrackingOptions off;
  off.enabled = false;
  RollingReference reference = Stored(View("aero1.jpg", 0), off);
  EXPECT_FALSE(reference.Track(View("aero1.jpg", 5), {0, 0}).has_value());
  EXPECT_EQ(reference.turn_deg(), 0);
}

TEST(RollingReferenceTest, RejectsADeadBandBeyondTheRange) {
  RollTrackingOptions o;
  o.dead_band_deg = o.max_deg;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("dead band"), std::string::npos) << error;
  EXPECT_THROW(RollingReference{o}, std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
