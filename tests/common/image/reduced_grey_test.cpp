#include "common/image/reduced_grey.hpp"

#include <gtest/gtest.h>

#include <cstdint>

namespace kapfix {
namespace {

TEST(ReducedGreyTest, AveragesEachBlockOfAGreyPlane) {
  cv::Mat plane(4, 6, CV_8UC1);
  for (int y = 0; y < plane.rows; ++y) {
    for (int x = 0; x < plane.cols; ++x)
      plane.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(10 * x + y);
  }
  const cv::Mat reduced = ReducedGrey(plane, 2);
  ASSERT_EQ(reduced.type(), CV_32FC1);
  ASSERT_EQ(reduced.size(), cv::Size(3, 2));
  // Block (1, 1): x 2…3, y 2…3 → (22 + 32 + 23 + 33) / 4.
  EXPECT_FLOAT_EQ(reduced.at<float>(1, 1), 27.5F);
  EXPECT_FLOAT_EQ(reduced.at<float>(0, 0), 5.5F);
}

TEST(ReducedGreyTest, TakesTheMeanOfThreeChannels) {
  const cv::Mat plane(2, 2, CV_8UC3, cv::Scalar(30, 60, 120));
  const cv::Mat reduced = ReducedGrey(plane, 1);
  ASSERT_EQ(reduced.type(), CV_32FC1);
  EXPECT_FLOAT_EQ(reduced.at<float>(1, 0), 70.F);
}

}  // namespace
}  // namespace kapfix
