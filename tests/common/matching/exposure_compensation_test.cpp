#include "common/matching/exposure_compensation.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "common/image/color_channel.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

const cv::Mat& AeroPlane() {
  static const cv::Mat plane =
      ExtractChannel(testing::LoadOpenCvPhoto("aero1.jpg"), ColorChannel::kGreen);
  return plane;
}

cv::Mat Scaled(const cv::Mat& plane, double gain) {
  cv::Mat out;
  plane.convertTo(out, -1, gain);
  return out;
}

TEST(ExposureCompensationTest, BringsADarkerFrameBackToTheReferenceBrightness) {
  const ExposureCompensation compensation(AeroPlane());
  const cv::Mat darker = Scaled(AeroPlane(), 0.7);
  double gain = 0;
  const cv::Mat applied = compensation.Apply(darker, &gain);
  EXPECT_NEAR(gain, 1.0 / 0.7, 0.01);
  EXPECT_NEAR(cv::mean(applied)[0], cv::mean(AeroPlane())[0], 0.5);
}

TEST(ExposureCompensationTest, ScalesEveryChannelOfAColourPlaneByOneGain) {
  const cv::Mat bgr = testing::LoadOpenCvPhoto("aero1.jpg");
  const ExposureCompensation compensation(bgr);
  // Darker, so that no channel saturates (a saturated pixel hides its share of the gain).
  EXPECT_NEAR(compensation.Gain(Scaled(bgr, 0.8)), 1.0 / 0.8, 0.01);
}

TEST(ExposureCompensationTest, AFrameAsBrightAsTheReferenceIsLeftUncopied) {
  const ExposureCompensation compensation(AeroPlane());
  double gain = 0;
  const cv::Mat applied = compensation.Apply(AeroPlane(), &gain);
  EXPECT_EQ(applied.data, AeroPlane().data);
  EXPECT_EQ(gain, 1.0);
}

TEST(ExposureCompensationTest, InPlaceGivesTheSamePlaneAsACopy) {
  const ExposureCompensation compensation(AeroPlane());
  const cv::Mat darker = Scaled(AeroPlane(), 0.7);
  double gain = 0;
  const cv::Mat copy = compensation.Apply(darker, &gain);
  cv::Mat in_place = darker.clone();
  EXPECT_EQ(compensation.ApplyInPlace(&in_place), gain);
  EXPECT_EQ(cv::norm(copy, in_place, cv::NORM_INF), 0.0);
}

TEST(ExposureCompensationTest, SixteenBitPlanesAreScaledToo) {
  cv::Mat wide;
  AeroPlane().convertTo(wide, CV_16U, 3.0);  // as the sum of three channels
  const ExposureCompensation compensation(wide);
  double gain = 0;
  const cv::Mat applied = compensation.Apply(Scaled(wide, 0.5), &gain);
  EXPECT_NEAR(gain, 2.0, 0.01);
  EXPECT_NEAR(cv::mean(applied)[0], cv::mean(wide)[0], 1.0);
}

TEST(ExposureCompensationTest, TheGainIsHeldWithinItsBounds) {
  const ExposureCompensation compensation(AeroPlane());
  EXPECT_EQ(compensation.Gain(Scaled(AeroPlane(), 0.1)), ExposureCompensation::kMaxGain);
  const cv::Mat white(AeroPlane().size(), CV_8UC1, cv::Scalar(255));
  const ExposureCompensation from_black(cv::Mat(AeroPlane().size(), CV_8UC1, cv::Scalar(2)));
  EXPECT_EQ(from_black.Gain(white), 1.0 / ExposureCompensation::kMaxGain);
}

TEST(ExposureCompensationTest, ABlackFrameOrNoReferenceGivesUnitGain) {
  const cv::Mat black(AeroPlane().size(), CV_8UC1, cv::Scalar(0));
  EXPECT_EQ(ExposureCompensation(AeroPlane()).Gain(black), 1.0);
  EXPECT_EQ(ExposureCompensation().Gain(AeroPlane()), 1.0);
}

TEST(ExposureCompensationTest, AnEmptyReferenceIsRefused) {
  EXPECT_THROW(ExposureCompensation(cv::Mat()), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
