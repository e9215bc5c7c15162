// The loop knows its calibration (issue 9): flown with the lens calibration off by a factor
// anywhere in 0.6…1.6, the predictive controller's online estimate of deg per px ends within
// 10 % of the truth after 20 s (500 frames at 25 frames/s) and the loop then holds the view
// as well as with an exact calibration.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/evaluation/closed_loop_evaluation.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

constexpr int kFrames = 500;  // 20 s at 25 frames/s

ClosedLoopFigures Fly(double calibration_error, bool adapt) {
  ClosedLoopOptions options;
  options.frames = kFrames;
  options.world.calibration_error = calibration_error;
  options.predictive.adapt_calibration = adapt;
  return EvaluateClosedLoop(testing::LoadOpenCvPhoto("fruits.jpg"), options);
}

// [px] RMS view error over the flight's second half.
double LateRms(const ClosedLoopFigures& f) {
  double sum = 0;
  const std::size_t half = f.view_offsets.size() / 2;
  for (std::size_t i = half; i < f.view_offsets.size(); ++i) {
    sum += f.view_offsets[i].dot(f.view_offsets[i]);
  }
  return std::sqrt(sum / static_cast<double>(f.view_offsets.size() - half));
}

class OnlineCalibrationTest : public ::testing::TestWithParam<double> {};

TEST_P(OnlineCalibrationTest, EstimateEndsWithinTenPercentAfterTwentySeconds) {
  const ClosedLoopFigures f = Fly(GetParam(), /*adapt=*/true);
  EXPECT_NEAR(f.deg_per_px_estimate_ratio, 1.0, 0.1) << "σ " << f.deg_per_px_estimate_sigma;
  EXPECT_TRUE(f.deg_per_px_estimate_trusted);
}

TEST_P(OnlineCalibrationTest, LoopHoldsAsWithAnExactCalibrationOnceAdapted) {
  static const double exact = LateRms(Fly(1.0, /*adapt=*/false));
  const double adapted = LateRms(Fly(GetParam(), /*adapt=*/true));
  // The issue allows 1.5 ×; the loop adapted holds within 1.2 × (measured 0.99–1.02 ×), which
  // an unadapted loop misses at either end (see below).
  EXPECT_LT(adapted, 1.2 * exact) << adapted << " px against " << exact << " px exact";
}

INSTANTIATE_TEST_SUITE_P(CalibrationErrors, OnlineCalibrationTest, ::testing::Values(0.6, 1.6),
                         [](const ::testing::TestParamInfo<double>& param) {
                           return param.param < 1 ? std::string("Low") : std::string("High");
                         });

// The per-frame trace shows the calibration the controller acts on moving from the stored one
// to the truth, and what it acted on (P, the last step extrapolated or the swing model).
TEST(OnlineCalibrationTest, ThePanForecastTraceFollowsTheCalibrationToTheTruth) {
  const ClosedLoopFigures f = Fly(1.6, /*adapt=*/true);
  ASSERT_EQ(f.pan_forecast.size(), f.view_offsets.size());
  ASSERT_EQ(f.tilt_forecast.size(), f.view_offsets.size());
  EXPECT_DOUBLE_EQ(f.pan_forecast.front().calibration_ratio, 1.6);
  EXPECT_NEAR(f.pan_forecast.back().calibration_ratio, 1.0, 0.1);
  EXPECT_EQ(f.pan_forecast.back().forecaster, 2.0);  // the swing model, once fitted
  EXPECT_GE(f.pan_forecast.back().weight, 0.0);
  EXPECT_LE(f.pan_forecast.back().weight, 1.0);
}

TEST(OnlineCalibrationTest, WithoutAdaptationAWrongCalibrationCostsTheLoop) {
  // The same flights with the estimate only reported: the control for the test above. A
  // calibration too small costs less since the swing's state is filtered (1.5 ×, from 2 ×);
  // too large still rings (5 ×).
  const double exact = LateRms(Fly(1.0, /*adapt=*/false));
  EXPECT_GT(LateRms(Fly(0.6, /*adapt=*/false)), 1.3 * exact);
  EXPECT_GT(LateRms(Fly(1.6, /*adapt=*/false)), 2.0 * exact);
}

}  // namespace
}  // namespace kapfix
