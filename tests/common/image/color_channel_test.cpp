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

TEST(ColorChannelTest, RgbKeepsTheThreeChannelsOfTheFrame) {
  const cv::Mat bgr(2, 2, CV_8UC3, cv::Scalar(10, 20, 30));
  const cv::Mat rgb = ExtractChannel(bgr, ColorChannel::kRgb);
  ASSERT_EQ(rgb.type(), CV_8UC3);
  EXPECT_EQ(rgb.at<cv::Vec3b>(1, 0), cv::Vec3b(10, 20, 30));
}

TEST(ColorChannelTest, RgbCopiesAGreyFrameIntoEveryChannel) {
  const cv::Mat grey(2, 3, CV_8UC1, cv::Scalar(77));
  const cv::Mat rgb = ExtractChannel(grey, ColorChannel::kRgb);
  ASSERT_EQ(rgb.type(), CV_8UC3);
  EXPECT_EQ(rgb.at<cv::Vec3b>(1, 2), cv::Vec3b(77, 77, 77));
}

TEST(ColorChannelTest, ParsesItsNames) {
  EXPECT_EQ(ParseColorChannel("rgb"), ColorChannel::kRgb);
  EXPECT_EQ(ParseColorChannel("rgb-sum"), ColorChannel::kRgbSum);
  EXPECT_EQ(ParseColorChannel("green"), ColorChannel::kGreen);
  EXPECT_FALSE(ParseColorChannel("blue").has_value());
  for (const ColorChannel c : {ColorChannel::kGreen, ColorChannel::kRgb, ColorChannel::kRgbSum}) {
    EXPECT_EQ(ParseColorChannel(ToString(c)), c);
  }
}

}  // namespace
}  // namespace kapfix
