#include "common/evaluation/closed_loop_evaluation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

// The kite scene (aerial photo, A = 100 px, T = 40 frames, gusts, one frame of servo
// latency), 300 frames, flown once per controller and shared by the tests below.
class ClosedLoopEvaluationTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const cv::Mat scene = testing::LoadOpenCvPhoto("aero1.jpg");
    ClosedLoopOptions options;
    options.frames = 300;
    options.controller = "p";
    p_ = new ClosedLoopFigures(EvaluateClosedLoop(scene, options));
    options.controller = "predictive";
    predictive_ = new ClosedLoopFigures(EvaluateClosedLoop(scene, options));
  }
  static void TearDownTestSuite() {
    delete p_;
    delete predictive_;
    p_ = predictive_ = nullptr;
  }

  static const ClosedLoopFigures* p_;
  static const ClosedLoopFigures* predictive_;
};

const ClosedLoopFigures* ClosedLoopEvaluationTest::p_ = nullptr;
const ClosedLoopFigures* ClosedLoopEvaluationTest::predictive_ = nullptr;

TEST_F(ClosedLoopEvaluationTest, PredictiveHoldsTheViewFarCloserThanPlainP) {
  // Measured at 300 frames: p ≈ 18 px, predictive ≈ 3 px (the start-up transient weighs more
  // in a shorter flight).
  EXPECT_LT(predictive_->rms_error_px, 0.3 * p_->rms_error_px)
      << "predictive " << predictive_->rms_error_px << " px, p " << p_->rms_error_px << " px";
}

TEST_F(ClosedLoopEvaluationTest, BothControllersKeepTheViewFarInsideTheOpenLoopSwing) {
  EXPECT_GT(p_->open_loop_rms_px, 40.0);  // the swing they are fighting
  EXPECT_LT(p_->rms_error_px, 0.5 * p_->open_loop_rms_px);
  EXPECT_LT(predictive_->rms_error_px, 0.1 * p_->open_loop_rms_px);
}

TEST_F(ClosedLoopEvaluationTest, PredictiveControllerActsOnItsForecastAfterTheStart) {
  EXPECT_GT(predictive_->predicting_pct, 90.0);
  EXPECT_DOUBLE_EQ(p_->predicting_pct, 0.0);
}

TEST_F(ClosedLoopEvaluationTest, LockIsHeldThroughout) {
  EXPECT_DOUBLE_EQ(predictive_->lock_lost_pct, 0.0);
  EXPECT_DOUBLE_EQ(p_->lock_lost_pct, 0.0);
}

TEST_F(ClosedLoopEvaluationTest, RecordsOneEntryPerFrame) {
  EXPECT_EQ(predictive_->frames, 300);
  EXPECT_EQ(predictive_->view_offsets.size(), 300u);
  EXPECT_EQ(predictive_->measured_x.size(), 300u);
  EXPECT_EQ(predictive_->angles.size(), 300u);
  EXPECT_GT(predictive_->fps, 0.0);
  EXPECT_LE(predictive_->loop_latency_p50_ms, predictive_->loop_latency_p99_ms);
}

TEST(ClosedLoopEvaluationLimitsTest, ServoAnglesNeverLeaveTheServoLimits) {
  ClosedLoopOptions options;
  options.frames = 120;
  // The swing needs ±10° of pan (100 px at 10 px/°); allow half of it.
  options.platform.pan.min_deg = -5;
  options.platform.pan.max_deg = 5;
  options.platform.tilt.min_deg = -1;
  options.platform.tilt.max_deg = 1;
  const ClosedLoopFigures f = EvaluateClosedLoop(testing::LoadOpenCvPhoto("aero1.jpg"), options);
  double lowest = 0, highest = 0;
  for (const ServoTargets& a : f.angles) {
    EXPECT_GE(a.pan_deg, -5.0);
    EXPECT_LE(a.pan_deg, 5.0);
    EXPECT_GE(a.tilt_deg, -1.0);
    EXPECT_LE(a.tilt_deg, 1.0);
    lowest = std::min(lowest, a.pan_deg);
    highest = std::max(highest, a.pan_deg);
  }
  // The controller did push against both limits (the output stops half the backlash short).
  EXPECT_LT(lowest, -4.9);
  EXPECT_GT(highest, 4.9);
}

TEST(ClosedLoopEvaluationOptionsTest, RejectsAnUnknownController) {
  ClosedLoopOptions options;
  options.controller = "bang-bang";
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("bang-bang"), std::string::npos);
  EXPECT_THROW(EvaluateClosedLoop(testing::SmoothTexture({600, 600}, 1), options),
               std::invalid_argument);
}

TEST(ClosedLoopEvaluationOptionsTest, BoatSearchesAndControlsAlongY) {
  const ClosedLoopOptions options =
      ClosedLoopOptions::ForMotion(SimulatedPlatformOptions::Motion::kBoat);
  EXPECT_EQ(options.fixation.search.axis, SearchAxis::kY);
  EXPECT_EQ(options.platform.motion, SimulatedPlatformOptions::Motion::kBoat);
  EXPECT_TRUE(options.IsValid(nullptr));
}

// The figures for the report (issue 3), 600 frames; slow, so not run by default:
//   kapfix_common_tests --gtest_also_run_disabled_tests --gtest_filter='ClosedLoopReport*'
TEST(ClosedLoopReport, DISABLED_SixHundredFramesPerControllerAndLatency) {
  const cv::Mat scene = testing::LoadOpenCvPhoto("aero1.jpg");
  std::printf("%-6s %-10s %7s %8s %6s %6s %6s %7s %7s %7s %7s\n", "motion", "controller", "latency",
              "rms_px", "x_px", "y_px", "open", "lost%", "fps", "p50_ms", "p99_ms");
  for (const auto motion :
       {SimulatedPlatformOptions::Motion::kKite, SimulatedPlatformOptions::Motion::kBoat}) {
    for (const int latency : {1, 0}) {
      double rms[2] = {0, 0};
      for (const int k : {0, 1}) {
        ClosedLoopOptions options = ClosedLoopOptions::ForMotion(motion);
        options.frames = 600;
        options.controller = k == 0 ? "p" : "predictive";
        options.platform.pan.latency_frames = latency;
        options.platform.tilt.latency_frames = latency;
        const ClosedLoopFigures f = EvaluateClosedLoop(scene, options);
        rms[k] = f.rms_error_px;
        std::printf("%-6s %-10s %7d %8.2f %6.2f %6.2f %6.1f %7.1f %7.0f %7.3f %7.3f\n",
                    motion == SimulatedPlatformOptions::Motion::kKite ? "kite" : "boat",
                    options.controller.c_str(), latency, f.rms_error_px, f.rms_error_x_px,
                    f.rms_error_y_px, f.open_loop_rms_px, f.lock_lost_pct, f.fps,
                    f.loop_latency_p50_ms, f.loop_latency_p99_ms);
      }
      EXPECT_LT(rms[1], rms[0]);
    }
  }
}

}  // namespace
}  // namespace kapfix
