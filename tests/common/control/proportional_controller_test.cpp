#include "common/control/proportional_controller.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <vector>

namespace kapfix {
namespace {

constexpr LensCalibration kLens{0.1, 0.2};  // [deg/px]

ControlInput Measured(double dx, double dy, double dt_s = 0.04) {
  ControlInput input;
  input.displacement_px = {dx, dy};
  input.confidence = 0.9;
  input.found = true;
  input.dt_s = dt_s;
  return input;
}

TEST(ProportionalControllerTest, PositiveDisplacementGivesAPositiveCorrection) {
  ProportionalController c({}, kLens);
  const ServoTargets t = c.Update(Measured(10, -5), {1.0, 2.0});
  EXPECT_DOUBLE_EQ(t.pan_deg, 1.0 + 10 * 0.1);
  EXPECT_DOUBLE_EQ(t.tilt_deg, 2.0 - 5 * 0.2);
}

TEST(ProportionalControllerTest, GainScalesTheCorrection) {
  ControllerGains gains;
  gains.p = 0.5;
  ProportionalController c(gains, kLens);
  EXPECT_DOUBLE_EQ(c.Update(Measured(10, 0), {}).pan_deg, 0.5);
}

TEST(ProportionalControllerTest, DisplacementInsideTheDeadBandHoldsThatAxis) {
  ControllerGains gains;
  gains.dead_band_px = 1.0;
  ProportionalController c(gains, kLens);
  const ServoTargets t = c.Update(Measured(0.9, 1.0), {3.0, 4.0});
  EXPECT_DOUBLE_EQ(t.pan_deg, 3.0);
  EXPECT_DOUBLE_EQ(t.tilt_deg, 4.0 + 0.2);
}

TEST(ProportionalControllerTest, NotFoundHoldsTheServos) {
  ProportionalController c({}, kLens);
  ControlInput input = Measured(50, 50);
  input.found = false;
  const ServoTargets t = c.Update(input, {3.0, 4.0});
  EXPECT_DOUBLE_EQ(t.pan_deg, 3.0);
  EXPECT_DOUBLE_EQ(t.tilt_deg, 4.0);
}

TEST(ProportionalControllerTest, NotFoundWithAReturnHeadsThereAtTheRateLimit) {
  ControllerGains gains;
  gains.rate_limit_deg_per_s = 10;
  ProportionalController c(gains, kLens);
  ControlInput input = Measured(50, 50, 0.1);
  input.found = false;
  input.return_to = ServoTargets{0.0, 5.0};
  const ServoTargets first = c.Update(input, {3.0, 4.0});
  EXPECT_DOUBLE_EQ(first.pan_deg, 2.0);
  EXPECT_DOUBLE_EQ(first.tilt_deg, 5.0);
  EXPECT_DOUBLE_EQ(c.Update(input, {3.0, 4.0}).pan_deg, 1.0);  // from its own last command
}

TEST(ProportionalControllerTest, RateLimitBoundsTheMovePerSecond) {
  ControllerGains gains;
  gains.rate_limit_deg_per_s = 10;
  ProportionalController c(gains, kLens);
  const ServoTargets t = c.Update(Measured(100, -100, 0.05), {0, 0});  // asks 10° and −20°
  EXPECT_DOUBLE_EQ(t.pan_deg, 0.5);
  EXPECT_DOUBLE_EQ(t.tilt_deg, -0.5);
}

// The angles a frame was seen through lag the commands by the actuation delay (2 frames
// here): the rate limit still lets the commands advance every frame.
TEST(ProportionalControllerTest, UnderADelayTheRateLimitLetsTheCommandsAdvanceEveryFrame) {
  ControllerGains gains;
  gains.rate_limit_deg_per_s = 10;
  ProportionalController c(gains, kLens);
  std::vector<double> sent = {0, 0};  // what the servo had been sent before
  for (int frame = 0; frame < 4; ++frame) {
    const double seen = sent[sent.size() - 2];  // the command of two frames ago
    sent.push_back(c.Update(Measured(100, 0, 0.05), {seen, 0}).pan_deg);
  }
  EXPECT_DOUBLE_EQ(sent.back(), 2.0);  // 4 frames × 0.5°, not 2 × 0.5°
}

TEST(ProportionalControllerTest, RateLimitWithoutElapsedTimeHolds) {
  ControllerGains gains;
  gains.rate_limit_deg_per_s = 10;
  ProportionalController c(gains, kLens);
  EXPECT_DOUBLE_EQ(c.Update(Measured(100, 0, 0.0), {1.0, 0}).pan_deg, 1.0);
}

TEST(ProportionalControllerTest, RejectsNegativeGainsAndAZeroCalibration) {
  ControllerGains gains;
  gains.p = -1;
  EXPECT_THROW(ProportionalController(gains, kLens), std::invalid_argument);
  EXPECT_THROW(ProportionalController({}, LensCalibration{0, 0.1}), std::invalid_argument);
}

TEST(ProportionalControllerTest, AnAxisTheFrameDidNotMeasureHoldsWhileTheOtherIsCorrected) {
  ProportionalController c({}, kLens);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const ServoTargets t = c.Update(Measured(10, nan), {1.0, 2.0});
  EXPECT_DOUBLE_EQ(t.pan_deg, 1.0 + 10 * 0.1);
  EXPECT_DOUBLE_EQ(t.tilt_deg, 2.0);
}

}  // namespace
}  // namespace kapfix
