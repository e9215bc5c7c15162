#include "common/control/pid_controller.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace kapfix {
namespace {

constexpr LensCalibration kLens{0.1, 0.1};  // [deg/px]

ControlInput Measured(double dx, double dt_s = 0.5) {
  ControlInput input;
  input.displacement_px = {dx, 0};
  input.confidence = 0.9;
  input.found = true;
  input.dt_s = dt_s;
  return input;
}

ControllerGains Gains(double p, double i, double d) {
  ControllerGains gains;
  gains.p = p;
  gains.i = i;
  gains.d = d;
  return gains;
}

TEST(PidControllerTest, IntegratorGrowsWithAConstantDisplacement) {
  PidController c(Gains(0, 1, 0), kLens);
  // ∫ 2 px dt over 0.5 s steps: 1, 2, 3 px·s; i = 1/s; 0.1 °/px.
  EXPECT_DOUBLE_EQ(c.Update(Measured(2), {}).pan_deg, 0.1);
  EXPECT_DOUBLE_EQ(c.Update(Measured(2), {}).pan_deg, 0.2);
  EXPECT_DOUBLE_EQ(c.Update(Measured(2), {}).pan_deg, 0.3);
  EXPECT_DOUBLE_EQ(c.integral().x, 3.0);
}

TEST(PidControllerTest, IntegralContributionIsClampedToItsLimit) {
  ControllerGains gains = Gains(0, 2, 0);
  gains.integral_limit_px = 5;
  PidController c(gains, kLens);
  ServoTargets t;
  for (int k = 0; k < 20; ++k) t = c.Update(Measured(10), {});
  EXPECT_DOUBLE_EQ(t.pan_deg, 5 * 0.1);
  // No wind-up to unwind: one frame of the opposite sign already reduces the command.
  EXPECT_LT(c.Update(Measured(-10), {}).pan_deg, 5 * 0.1);
}

TEST(PidControllerTest, DerivativeActsOnTheChangeOfDisplacement) {
  PidController c(Gains(0, 0, 0.5), kLens);
  EXPECT_DOUBLE_EQ(c.Update(Measured(4), {}).pan_deg, 0.0);  // no previous frame yet
  // (10 − 4) px / 0.5 s · 0.5 s · 0.1 °/px
  EXPECT_DOUBLE_EQ(c.Update(Measured(10), {}).pan_deg, 0.6);
}

TEST(PidControllerTest, ResetClearsTheIntegral) {
  PidController c(Gains(0, 1, 0), kLens);
  c.Update(Measured(2), {});
  c.Reset();
  EXPECT_DOUBLE_EQ(c.integral().x, 0.0);
  EXPECT_DOUBLE_EQ(c.Update(Measured(2), {}).pan_deg, 0.1);
}

TEST(PidControllerTest, ProportionalTermCorrectsFromTheCurrentAngle) {
  PidController c(Gains(1, 0, 0), kLens);
  EXPECT_DOUBLE_EQ(c.Update(Measured(-7), {2.0, 0}).pan_deg, 2.0 - 0.7);
}

TEST(PidControllerTest, AnAxisTheFrameDidNotMeasureHoldsAndKeepsItsIntegral) {
  PidController c(Gains(1.0, 1.0, 0.0), kLens);
  ControlInput both = Measured(4);
  both.displacement_px.y = 2;
  c.Update(both, {});  // integral (2, 1) px·s over 0.5 s
  ControlInput x_only = Measured(4);
  x_only.displacement_px.y = std::numeric_limits<double>::quiet_NaN();
  const ServoTargets held = c.Update(x_only, {0.0, 3.0});
  EXPECT_DOUBLE_EQ(held.tilt_deg, 3.0);  // no correction, not even the integral's
  EXPECT_GT(held.pan_deg, 0.4);
  // Measured again, Y's integral goes on from the 1 px·s it had: 2 px·s, and P's 2 px.
  const ServoTargets back = c.Update(both, {0.0, 0.0});
  EXPECT_NEAR(back.tilt_deg, (2 + 2.0) * 0.1, 1e-9);
}

}  // namespace
}  // namespace kapfix
