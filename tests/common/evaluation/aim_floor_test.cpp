#include "common/evaluation/aim_floor.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace kapfix {
namespace {

// A damped swing in x with a slower sway in y [px], one sample per frame.
std::vector<cv::Point2d> Swing(int frames) {
  std::vector<cv::Point2d> offsets;
  for (int t = 0; t < frames; ++t) {
    offsets.emplace_back(60.0 * std::exp(-0.002 * t) * std::sin(2 * M_PI * t / 45.0),
                         15.0 * std::sin(2 * M_PI * t / 170.0 + 0.4));
  }
  return offsets;
}

TEST(AimFloorTest, WithoutJitterAKnownSwingLeavesNothing) {
  EXPECT_NEAR(AimFloorRms(Swing(400), 2, 0), 0.0, 1e-12);
}

TEST(AimFloorTest, ASteadyDriftUnderOneFrameOfJitterLeavesHalfAStep) {
  std::vector<cv::Point2d> drift;
  for (int t = 0; t < 100; ++t) drift.emplace_back(6.0 * t, -8.0 * t);  // 10 px per frame
  EXPECT_NEAR(AimFloorRms(drift, 2, 1), 5.0, 1e-9);
}

TEST(AimFloorTest, UnderOneFrameOfJitterItIsHalfTheRmsStepOfAnySeries) {
  // Frame s shows the aim at s or s − 1 (each half the time), and that aim is the mean of
  // the view at its two frames: the miss is half a step either way.
  const std::vector<cv::Point2d> swing = Swing(300);
  double sum = 0;
  int steps = 0;
  for (int s = 3; s + 1 < 300; ++s) {  // the frames counted (lead 2, spread 1)
    const cv::Point2d ahead = swing[s + 1] - swing[s], behind = swing[s] - swing[s - 1];
    sum += 0.5 * ahead.dot(ahead) + 0.5 * behind.dot(behind);
    ++steps;
  }
  EXPECT_NEAR(AimFloorRms(swing, 2, 1), 0.5 * std::sqrt(sum / steps), 1e-9);
}

TEST(AimFloorTest, MoreJitterLeavesMore) {
  const std::vector<cv::Point2d> swing = Swing(400);
  const double one = AimFloorRms(swing, 2, 1), three = AimFloorRms(swing, 2, 3);
  EXPECT_GT(one, 0.5);
  EXPECT_GT(three, 1.5 * one);
}

TEST(AimFloorTest, TooFewFramesIsNotANumber) {
  EXPECT_TRUE(std::isnan(AimFloorRms(Swing(3), 2, 1)));
}

TEST(AimFloorTest, ALeadBelowOneFrameIsRefused) {
  EXPECT_THROW(AimFloorRms(Swing(50), 0, 1), std::invalid_argument);
  EXPECT_THROW(AimFloorRms(Swing(50), 2, -1), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
