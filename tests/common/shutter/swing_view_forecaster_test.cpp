#include "common/shutter/swing_view_forecaster.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace kapfix {
namespace {

TEST(Ar2PeriodFramesTest, UndampedSinusoidGivesItsPeriod) {
  const double a1 = 2 * std::cos(2 * std::numbers::pi / 40.0);
  const auto period = Ar2PeriodFrames({a1, -1.0, 0.0}, 0.8);
  ASSERT_TRUE(period);
  EXPECT_NEAR(*period, 40.0, 1e-9);
}

TEST(Ar2PeriodFramesTest, RealRootsHaveNoPeriod) {
  EXPECT_FALSE(Ar2PeriodFrames({0.5, 0.1, 0.0}, 0.8));
}

TEST(SwingViewForecasterTest, SeesTheSwingPeriodInTheServoAngles) {
  SwingViewForecaster forecaster;
  for (int i = 0; i < 200; ++i) {
    ShutterFrame frame;
    frame.time_us = i * 33333;
    frame.trusted = true;
    frame.offset_px = {0.5 * std::sin(i * 0.7), 0.3 * std::cos(i * 1.3)};
    frame.pan_deg = 8.0 * std::sin(2 * std::numbers::pi * i / 40.0) * std::exp(-i / 400.0);
    frame.tilt_deg = 0.1;
    forecaster.Observe(frame);
  }
  EXPECT_TRUE(forecaster.trained());
  const auto period = forecaster.period_frames();
  ASSERT_TRUE(period);
  EXPECT_NEAR(*period, 40.0, 0.5);
}

TEST(SwingViewForecasterTest, UntrainedBeforeItHasMeasuredItsError) {
  SwingViewForecaster forecaster;
  ShutterFrame frame;
  frame.trusted = true;
  forecaster.Observe(frame);
  EXPECT_FALSE(forecaster.trained());
}

}  // namespace
}  // namespace kapfix
