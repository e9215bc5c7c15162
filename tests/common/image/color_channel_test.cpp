#include "common/image/color_channel.hpp"

#include <gtest/gtest.h>

namespace kapfix {
namespace {

TEST(ColorChannelTest, GreenTakesTheMiddleBgrPlane) {
  const cv::Mat bgr(2, 2, CV_8UC3, cv::Scalar(10, 20, 30));
  const cv::Mat green = ExtractChannel(bgr, ColorChannel::kGreen);
  ASSERT_EQ(green.type(), CV_8UC1);
  EXPECT_EQ(green.at<std::uint8_t>(1, 1), 20);
}

TEST(ColorChannelTest, RgbSumAddsThePlanesWithoutOverflow) {
  const cv::Mat bgr(2, 2, CV_8UC3, cv::Scalar(255, 254, 253));
  const cv::Mat sum = ExtractChannel(bgr, ColorChannel::kRgbSum);
  ASSERT_EQ(sum.type(), CV_16UC1);
  EXPECT_EQ(sum.at<std::uint16_t>(0, 0), 762);
}

TEST(ColorChannelTest, RefusesFloatFrames) {
  EXPECT_THROW(ExtractChannel(cv::Mat(2, 2, CV_32FC1), ColorChannel::kGreen),
               std::invalid_argument);
}

TEST(ColorChannelTest, ParsesItsNames) {
  EXPECT_EQ(ParseColorChannel("rgb"), ColorChannel::kRgbSum);
  EXPECT_EQ(ParseColorChannel("green"), ColorChannel::kGreen);
  EXPECT_FALSE(ParseColorChannel("blue").has_value());
}

}  // namespace
}  // namespace kapfix
