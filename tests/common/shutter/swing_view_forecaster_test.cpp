#include "common/shutter/swing_view_forecaster.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

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

// A frame of a residual the loop pulls back to the reference at 0.5 per frame under white
// disturbances (σ 1 px per axis), seen through a 40-frame swing of the pan servo.
class HeldResidual {
 public:
  ShutterFrame Next() {
    offset_ = 0.5 * offset_ + cv::Point2d(normal_(random_), normal_(random_));
    return At(offset_);
  }
  ShutterFrame At(cv::Point2d offset) {
    ShutterFrame frame;
    frame.time_us = index_ * 33333;
    frame.trusted = true;
    frame.offset_px = offset;
    frame.pan_deg = 8.0 * std::sin(2 * std::numbers::pi * index_ / 40.0);
    ++index_;
    return frame;
  }

 private:
  std::mt19937 random_{7};
  std::normal_distribution<double> normal_{0.0, 1.0};
  cv::Point2d offset_{0, 0};
  int index_ = 0;
};

TEST(SwingViewForecasterTest, MeasuresTheRateTheResidualRevertsAt) {
  SwingViewForecaster forecaster(200);
  HeldResidual residual;
  for (int i = 0; i < 400; ++i) forecaster.Observe(residual.Next());
  EXPECT_NEAR(forecaster.reversion().x, 0.5, 0.15);
  EXPECT_NEAR(forecaster.reversion().y, 0.5, 0.15);
}

TEST(SwingViewForecasterTest, FarForecastAfterAGustStaysWhereTheLoopHoldsTheView) {
  // A gust pushes the residual 1.5 px further each frame for 6 frames (to 9 px); the loop
  // has held it within a few pixels for 200 frames and will pull it back, so 30 frames on
  // the view is forecast no further out than the next frame, not extrapolated along the ramp.
  SwingViewForecaster forecaster;
  HeldResidual residual;
  for (int i = 0; i < 200; ++i) forecaster.Observe(residual.Next());
  for (int k = 1; k <= 6; ++k) forecaster.Observe(residual.At({1.5 * k, 0.0}));
  ASSERT_TRUE(forecaster.trained());
  const double next = forecaster.Forecast(1).x;
  EXPECT_LE(std::abs(forecaster.Forecast(30).x), std::abs(next) + 1e-9) << next;
  EXPECT_LT(std::abs(forecaster.Forecast(30).x), 10.0) << next;
}

TEST(SwingViewForecasterTest, KeepsTheSwingPeriodWhenItsFitIsLost) {
  SwingViewForecaster forecaster;
  HeldResidual residual;
  for (int i = 0; i < 200; ++i) forecaster.Observe(residual.Next());
  ASSERT_TRUE(forecaster.period_frames());
  // The servo angles then stop coming (not finite): the angle predictors bridge a few frames
  // and forget their fit; the swing has not stopped, its period is kept.
  for (int i = 0; i < 100; ++i) {
    ShutterFrame frame = residual.Next();
    frame.pan_deg = frame.tilt_deg = std::numeric_limits<double>::quiet_NaN();
    forecaster.Observe(frame);
  }
  const auto period = forecaster.period_frames();
  ASSERT_TRUE(period);
  EXPECT_NEAR(*period, 40.0, 1.0);
}

}  // namespace
}  // namespace kapfix
