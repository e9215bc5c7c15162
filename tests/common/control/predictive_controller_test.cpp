#include "common/control/predictive_controller.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "common/control/proportional_controller.hpp"
#include "common/sim/sim_random.hpp"

namespace kapfix {
namespace {

// A loop without images: the swing m(t) [px] plus an ideal servo whose angle shows in the
// view `lead` frames after the command (capture t → command → first frame showing it,
// t + lead). The controller measures d(t) = −(m(t) + angle(t) · px_per_deg), as a matcher
// would against the reference at frame 0 (SPEC §1).
class NumericLoop {
 public:
  NumericLoop(double px_per_deg, int lead) : px_per_deg_(px_per_deg), lead_(lead) {}

  static double Swing(int t) { return 100 * std::sin(2 * std::numbers::pi * t / 40.0); }

  // Runs frames 0 … frames − 1; returns the largest |view offset| over frames ≥ from.
  double Run(Controller& controller, int frames, int from) {
    double worst = 0;
    for (int t = 0; t < frames; ++t) {
      const double angle = AngleAt(t);
      const double offset = Swing(t) + angle * px_per_deg_;
      if (t >= from) worst = std::max(worst, std::abs(offset));
      ControlInput input;
      input.displacement_px = {-offset, 0};
      input.confidence = 1;
      input.found = true;
      input.dt_s = 0.04;
      commands_.push_back(controller.Update(input, {angle, 0}).pan_deg);
    }
    return worst;
  }

  double AngleAt(int t) const {
    const int sent = t - lead_;  // the command sent after capturing frame `sent`
    return sent >= 0 && sent < static_cast<int>(commands_.size()) ? commands_[sent] : 0.0;
  }

 private:
  double px_per_deg_;
  int lead_;
  std::deque<double> commands_;
};

ControllerGains NoDeadBand() {
  ControllerGains gains;
  gains.dead_band_px = 0;
  return gains;
}

PredictiveOptions Lead(int frames) {
  PredictiveOptions options;
  options.predictor.lead_frames = frames;
  return options;
}

ControlInput Measured(double dx) {
  ControlInput input;
  input.displacement_px = {dx, 0};
  input.confidence = 1;
  input.found = true;
  input.dt_s = 0.04;
  return input;
}

TEST(PredictiveControllerTest, HoldsAPureSwingWithinAFractionOfAPixel) {
  PredictiveController controller(NoDeadBand(), {0.1, 0.1}, Lead(2));
  NumericLoop loop(10, 2);
  EXPECT_LT(loop.Run(controller, 200, 40), 0.01);
  EXPECT_TRUE(controller.predicting_pan());
}

TEST(PredictiveControllerTest, PlainPTrailsTheSameSwingByTwoFramesOfMotion) {
  // Why prediction (SPEC §3): at 15.7 px per frame, two frames late is ~30 px.
  ProportionalController controller(NoDeadBand(), {0.1, 0.1});
  NumericLoop loop(10, 2);
  EXPECT_GT(loop.Run(controller, 200, 40), 25.0);
}

TEST(PredictiveControllerTest, ServoMountedTheOtherWayIsHeldThroughANegativeCalibration) {
  PredictiveController controller(NoDeadBand(), {-0.1, -0.1}, Lead(2));
  NumericLoop loop(-10, 2);
  EXPECT_LT(loop.Run(controller, 200, 40), 0.01);
}

TEST(PredictiveControllerTest, LongerServoLatencyIsPredictedFurtherAhead) {
  PredictiveController controller(NoDeadBand(), {0.1, 0.1}, Lead(4));
  NumericLoop loop(10, 4);
  EXPECT_LT(loop.Run(controller, 200, 60), 0.01);
}

TEST(PredictiveControllerTest, FirstSmallDisplacementIsCorrectedLikePlainP) {
  PredictiveController controller({}, {0.1, 0.1}, Lead(2));
  const ServoTargets t = controller.Update(Measured(3), {1.0, 0});
  EXPECT_DOUBLE_EQ(t.pan_deg, 1.0 + 0.3);
  EXPECT_FALSE(controller.predicting_pan());
}

TEST(PredictiveControllerTest, CoastsThroughAShortDropoutThenHolds) {
  PredictiveController controller(NoDeadBand(), {0.1, 0.1}, Lead(2));
  NumericLoop loop(10, 2);
  loop.Run(controller, 100, 0);
  ControlInput lost = Measured(0);
  lost.found = false;
  const ServoTargets current{1.0, 0.0};
  for (int k = 0; k < 3; ++k) {  // max_coast_frames
    EXPECT_NE(controller.Update(lost, current).pan_deg, current.pan_deg) << "dropout " << k;
  }
  EXPECT_DOUBLE_EQ(controller.Update(lost, current).pan_deg, current.pan_deg);
  EXPECT_FALSE(controller.predicting_pan());
}

// A lost lock (ControlInput::return_to): no bridging on a forecast fitted to what may have
// been wrong matches; the servos head for the return point the loop gives, at the rate limit.
TEST(PredictiveControllerTest, ALostLockHeadsForTheReturnPointInsteadOfCoasting) {
  ControllerGains gains = NoDeadBand();
  gains.rate_limit_deg_per_s = 25;  // 1° per 0.04 s frame
  PredictiveController controller(gains, {0.1, 0.1}, Lead(2));
  NumericLoop loop(10, 2);
  loop.Run(controller, 100, 0);
  ControlInput lost = Measured(0);
  lost.found = false;
  lost.return_to = ServoTargets{0.5, -0.5};
  const ServoTargets current{2.0, 0.0};
  const ServoTargets first = controller.Update(lost, current);
  EXPECT_LE(std::abs(first.pan_deg - loop.AngleAt(101)), 1.0 + 1e-9);  // from its last command
  ServoTargets target = first;
  for (int k = 0; k < 20; ++k) target = controller.Update(lost, current);
  EXPECT_DOUBLE_EQ(target.pan_deg, 0.5);
  EXPECT_DOUBLE_EQ(target.tilt_deg, -0.5);
  EXPECT_FALSE(controller.predicting_pan());
}

TEST(PredictiveControllerTest, ResetForgetsTheSwing) {
  PredictiveController controller(NoDeadBand(), {0.1, 0.1}, Lead(2));
  NumericLoop loop(10, 2);
  loop.Run(controller, 100, 0);
  controller.Reset();
  // Plain P again, on the calibration the online estimate left (the lens has not changed).
  const double deg_per_px = controller.calibration().pan_deg_per_px;
  EXPECT_NEAR(deg_per_px, 0.1, 0.002);
  EXPECT_DOUBLE_EQ(controller.Update(Measured(2), {}).pan_deg, 2 * deg_per_px);
  EXPECT_FALSE(controller.predicting_pan());
}

TEST(PredictiveControllerTest, CorrectionInsideTheDeadBandHolds) {
  ControllerGains gains;
  gains.dead_band_px = 0.5;
  PredictiveController controller(gains, {0.1, 0.1}, Lead(2));
  // A still view with a constant 0.3 px offset: the model forecasts 0.3 px, inside the band.
  for (int t = 0; t < 60; ++t) controller.Update(Measured(0.3 + 0.01 * (t % 3)), {});
  EXPECT_DOUBLE_EQ(controller.Update(Measured(0.3), {}).pan_deg, 0.0);
  EXPECT_TRUE(controller.predicting_pan());  // held by the band, not by the P fallback
}

TEST(PredictiveControllerTest, HandsOverToPWhenTheViewShowsItsForecastsFail) {
  // The servos never move (a belief that is wrong: the commands do not act), so the swing's
  // forecast is good but every forecast the controller acted on leaves the whole swing in
  // the view: worse than persistence's error. It must hand over to P.
  PredictiveController controller(NoDeadBand(), {0.1, 0.1}, Lead(2));
  for (int t = 0; t < 200; ++t) {
    controller.Update(Measured(-NumericLoop::Swing(t)), {});
  }
  EXPECT_DOUBLE_EQ(controller.pan_forecast_weight(), 0.0);
  EXPECT_FALSE(controller.predicting_pan());
}

TEST(PredictiveControllerTest, HandsOverGraduallyAndComesBackOnceItsForecastsWorkAgain) {
  // 200 frames whose commands do not act (as above), then a servo that works: the forecast
  // weight must fall through intermediate values (a blend, not a switch), reach P, and come
  // back to the forecast — again through intermediate values — once it forecasts well.
  PredictiveController controller(NoDeadBand(), {0.1, 0.1}, Lead(2));
  bool blended_down = false, blended_up = false;
  double lowest = 1;
  for (int t = 0; t < 200; ++t) {
    controller.Update(Measured(-NumericLoop::Swing(t)), {});
    const double w = controller.pan_forecast_weight();
    blended_down = blended_down || (w > 0 && w < 1);
    lowest = std::min(lowest, w);
  }
  std::vector<double> commands;
  for (int t = 200; t < 600; ++t) {
    const double angle = commands.size() >= 2 ? commands[commands.size() - 2] : 0.0;
    const double offset = NumericLoop::Swing(t) + angle * 10;
    commands.push_back(controller.Update(Measured(-offset), {angle, 0}).pan_deg);
    const double w = controller.pan_forecast_weight();
    blended_up = blended_up || (w > 0 && w < 1);
  }
  EXPECT_TRUE(blended_down);
  EXPECT_DOUBLE_EQ(lowest, 0.0);
  EXPECT_TRUE(blended_up);
  EXPECT_DOUBLE_EQ(controller.pan_forecast_weight(), 1.0);
  EXPECT_TRUE(controller.predicting_pan());
}

TEST(PredictiveControllerTest, KeepsItsForecastWhileTheViewShowsItWorks) {
  PredictiveController controller(NoDeadBand(), {0.1, 0.1}, Lead(2));
  NumericLoop loop(10.0, 2);
  loop.Run(controller, 300, 0);
  EXPECT_DOUBLE_EQ(controller.pan_forecast_weight(), 1.0);
  EXPECT_TRUE(controller.predicting_pan());
}

// The swing of NumericLoop plus a step gust every 25 frames (a push of up to ±20 px that
// stays), which the servo must follow and a damped pendulum cannot explain: the excitation
// the online calibration learns from.
double GustySwing(int t) {
  double gusts = 0;
  for (int k = 25; k <= t; k += 25) gusts += 20 * SimGaussian(11, 0, k / 25);
  return NumericLoop::Swing(t) + gusts;
}

// Flies `frames` frames of GustySwing against a lens with 10 px/deg, the controller's
// calibration `error` × the true 0.1 deg/px, with the servo showing in the view 2 frames
// after the command; returns the calibration the controller acts on at the end ÷ the truth.
double CalibrationRatioAfter(int frames, double error) {
  PredictiveController controller(NoDeadBand(), {0.1 * error, 0.1 * error}, Lead(2));
  std::vector<double> commands;
  for (int t = 0; t < frames; ++t) {
    const double angle = t >= 2 ? commands[static_cast<std::size_t>(t - 2)] : 0.0;
    const double offset = GustySwing(t) + angle * 10;
    commands.push_back(controller.Update(Measured(-offset), {angle, 0}).pan_deg);
  }
  return controller.calibration().pan_deg_per_px / 0.1;
}

TEST(PredictiveControllerCalibrationTest, AWrongCalibrationIsCorrectedWithinThreeSeconds) {
  // 75 frames (3 s at 25 frames/s): trusted after ~20 fitted frames, then acted on at once
  // (a bounded step of at most 2× per 5 frames) rather than 10 % per 10 frames.
  for (const double error : {0.6, 1.6}) {
    EXPECT_NEAR(CalibrationRatioAfter(75, error), 1.0, 0.1) << "calibration x" << error;
  }
}

ControlInput Hinted(double dx, double pan_deg_per_px_hint) {
  ControlInput input = Measured(dx);
  input.pan_deg_per_px_hint = pan_deg_per_px_hint;
  return input;
}

TEST(PredictiveControllerCalibrationTest, ActsOnTheCallersHintBeforeItsEstimateIsTrusted) {
  PredictiveController controller(NoDeadBand(), {0.13, 0.1}, Lead(2));
  controller.Update(Hinted(-5, 0.1), {0, 0});
  ASSERT_FALSE(controller.pan_estimator().trusted());
  EXPECT_DOUBLE_EQ(controller.calibration().pan_deg_per_px, 0.1);
  EXPECT_DOUBLE_EQ(controller.calibration().tilt_deg_per_px, 0.1);  // no hint: stays
}

TEST(PredictiveControllerCalibrationTest, AHintOfTheOtherSignOrNoneIsNotActedOn) {
  PredictiveController controller(NoDeadBand(), {0.13, 0.1}, Lead(2));
  controller.Update(Hinted(-5, -0.1), {0, 0});
  controller.Update(Hinted(-5, std::numeric_limits<double>::quiet_NaN()), {0, 0});
  controller.Update(Hinted(-5, 0), {0, 0});
  EXPECT_DOUBLE_EQ(controller.calibration().pan_deg_per_px, 0.13);
}

// A trusted estimate outranks the hint: one 2× off, sent for 50 frames after the lock-on of
// CalibrationRatioAfter (calibration ×1.6), moves nothing.
TEST(PredictiveControllerCalibrationTest, ATrustedEstimateOutranksTheHint) {
  PredictiveController controller(NoDeadBand(), {0.16, 0.16}, Lead(2));
  std::vector<double> commands;
  for (int t = 0; t < 125; ++t) {
    const double angle = t >= 2 ? commands[static_cast<std::size_t>(t - 2)] : 0.0;
    const double offset = GustySwing(t) + angle * 10;
    const double hint = t < 75 ? 0.0 : 0.2;
    if (t == 75) {
      ASSERT_TRUE(controller.pan_estimator().trusted());
    }
    commands.push_back(controller.Update(Hinted(-offset, hint), {angle, 0}).pan_deg);
  }
  EXPECT_NEAR(controller.calibration().pan_deg_per_px, 0.1, 0.01);
}

TEST(PredictiveControllerEstimateTest, ReportsTheStoredCalibrationUntrustedBeforeAnyFit) {
  PredictiveController controller(NoDeadBand(), {0.1, 0.2}, Lead(2));
  const std::optional<ControlEstimate> estimate = controller.estimate();
  ASSERT_TRUE(estimate.has_value());
  EXPECT_DOUBLE_EQ(estimate->pan.deg_per_px, 0.1);
  EXPECT_DOUBLE_EQ(estimate->tilt.deg_per_px, 0.2);
  EXPECT_FALSE(estimate->pan.trusted);
  EXPECT_FALSE(std::isfinite(estimate->pan.relative_sigma));
}

TEST(PredictiveControllerEstimateTest, ReportsTheForecastWeightItActsOn) {
  PredictiveController controller(NoDeadBand(), {0.1, 0.1}, Lead(2));
  for (int t = 0; t < 200; ++t) controller.Update(Measured(-NumericLoop::Swing(t)), {});
  const std::optional<ControlEstimate> estimate = controller.estimate();
  ASSERT_TRUE(estimate.has_value());
  EXPECT_DOUBLE_EQ(estimate->pan.forecast_weight, controller.pan_forecast_weight());
  EXPECT_DOUBLE_EQ(estimate->pan.forecast_weight, 0.0);  // handed over (see above)
  EXPECT_DOUBLE_EQ(estimate->forecast_weight(),
                   0.5 * (estimate->pan.forecast_weight + estimate->tilt.forecast_weight));
}

TEST(PredictiveControllerEstimateTest, PlainPHasNoEstimate) {
  const ProportionalController controller(NoDeadBand(), {0.1, 0.1});
  EXPECT_FALSE(controller.estimate().has_value());
}

TEST(PredictiveControllerTest, AnAxisTheFrameDidNotMeasureCoastsOnItsForecast) {
  // Both axes swing; the servos stay at 0, so each frame shows the whole swing. Then one frame
  // is sure along X only (its Y is NaN): Y is aimed at its forecast, not held.
  PredictiveController controller(NoDeadBand(), {0.1, 0.1}, Lead(2));
  const auto swing = [](int t) { return NumericLoop::Swing(t); };
  for (int t = 0; t < 120; ++t) {
    ControlInput input = Measured(-swing(t));
    input.displacement_px.y = -swing(t);
    controller.Update(input, {0, 0});
  }
  ControlInput x_only = Measured(-swing(120));
  x_only.displacement_px.y = std::numeric_limits<double>::quiet_NaN();
  const ServoTargets target = controller.Update(x_only, {0, 0});
  EXPECT_TRUE(controller.predicting_tilt());
  // Cancelling the swing two frames ahead: −swing(122) px through 0.1 deg/px.
  EXPECT_NEAR(target.tilt_deg, -swing(122) * 0.1, 0.3);
}

}  // namespace
}  // namespace kapfix

namespace kapfix {
namespace {

// Issue 15, item 7: a gain change mid-flight keeps the swing models (bumpless). The loop runs
// 200 frames, then `change` acts on the controller, then 100 more frames: the largest view
// error over those.
double WorstAfterChange(const std::function<void(std::unique_ptr<Controller>*)>& change) {
  std::unique_ptr<Controller> controller =
      std::make_unique<PredictiveController>(NoDeadBand(), LensCalibration{0.1, 0.1}, Lead(2));
  std::vector<double> commands;
  double worst = 0;
  for (int t = 0; t < 300; ++t) {
    if (t == 200) change(&controller);
    const double angle = t >= 2 ? commands[static_cast<std::size_t>(t - 2)] : 0.0;
    const double offset = NumericLoop::Swing(t) + angle * 10;
    if (t >= 200) worst = std::max(worst, std::abs(offset));
    commands.push_back(controller->Update(Measured(-offset), {angle, 0}).pan_deg);
  }
  return worst;
}

TEST(PredictiveControllerGainsTest, TheSameGainsSentAgainCauseNoTransient) {
  EXPECT_LT(WorstAfterChange([](std::unique_ptr<Controller>* c) { (*c)->SetGains(NoDeadBand()); }),
            1.0);
}

TEST(PredictiveControllerGainsTest, AChangedGainCausesNoTransient) {
  ControllerGains softer = NoDeadBand();
  softer.p = 0.9;
  const double kept =
      WorstAfterChange([&softer](std::unique_ptr<Controller>* c) { (*c)->SetGains(softer); });
  // A rebuilt controller starts without a swing model: that is the transient a bumpless
  // change avoids.
  const double rebuilt = WorstAfterChange([&softer](std::unique_ptr<Controller>* c) {
    *c = std::make_unique<PredictiveController>(softer, LensCalibration{0.1, 0.1}, Lead(2));
  });
  EXPECT_LT(kept, 5.0);
  EXPECT_GT(rebuilt, 4 * kept) << "the control case shows no transient: " << rebuilt << " px";
}

TEST(PredictiveControllerGainsTest, InvalidGainsAreRefusedAndChangeNothing) {
  PredictiveController controller(NoDeadBand(), {0.1, 0.1}, Lead(2));
  ControllerGains bad = NoDeadBand();
  bad.p = -1;
  EXPECT_THROW(controller.SetGains(bad), std::invalid_argument);
  const ServoTargets t = controller.Update(Measured(5), {0, 0});
  EXPECT_NEAR(t.pan_deg, 0.5, 1e-9);  // p = 1 still: 5 px · 0.1 deg/px
}

}  // namespace
}  // namespace kapfix
