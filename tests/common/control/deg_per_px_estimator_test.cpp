#include "common/control/deg_per_px_estimator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

namespace kapfix {
namespace {

constexpr double kTrueDegPerPx = 0.1;  // [deg/px]

// A damped swing [px] around an offset, as the loop sees it. (Gusts, which break the swing's
// recurrence, are flown in the closed-loop tests: tests/common/evaluation.)
double Swing(int t) {
  return 60.0 * std::exp(-t / 400.0) * std::sin(2 * std::numbers::pi * t / 40.0) + 5.0;
}

// Servo moves that do not follow the swing (a step of up to ±2° every 10 frames, as the
// loop's corrections of gusts and lock-on are): the angle each frame is seen through and the
// measured displacement d = swing − angle / deg_per_px + noise.
void Fly(DegPerPxEstimator* estimator, double noise_px, int frames) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, noise_px);
  std::uniform_real_distribution<double> step(-2.0, 2.0);
  double angle = 0;
  for (int t = 0; t < frames; ++t) {
    if (t % 10 == 0) angle = step(rng);
    estimator->Add(angle, Swing(t) - angle / kTrueDegPerPx + noise(rng));
  }
}

TEST(DegPerPxEstimatorTest, FindsTheTrueDegPerPxUnderTwoPixelsOfNoise) {
  for (const double error : {0.6, 1.3, 1.6}) {
    for (const double noise : {1.0, 2.0}) {
      DegPerPxEstimator estimator(kTrueDegPerPx * error);
      Fly(&estimator, noise, 500);
      EXPECT_NEAR(estimator.estimate_deg_per_px() / kTrueDegPerPx, 1.0, 0.03)
          << error << " at " << noise << " px";
      // At 2 px the uncertainty stays above the trust threshold over 500 frames of these
      // moves: accurate, but not yet acted on.
      if (noise <= 1.0) {
        EXPECT_TRUE(estimator.trusted()) << error << ": σ " << estimator.relative_sigma();
      }
    }
  }
}

TEST(DegPerPxEstimatorTest, DoesNotTrustAServoThatOnlyFollowsTheSwing) {
  // A servo that cancels the swing exactly leaves nothing that tells its gain apart from the
  // swing's amplitude: any deg per px explains the frames.
  DegPerPxEstimator estimator(kTrueDegPerPx * 1.4);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (int t = 0; t < 400; ++t) {
    const double swing = 60.0 * std::sin(2 * std::numbers::pi * t / 40.0);
    estimator.Add(swing * kTrueDegPerPx, noise(rng));
  }
  EXPECT_FALSE(estimator.trusted()) << "σ " << estimator.relative_sigma();
}

TEST(DegPerPxEstimatorTest, IsNotTrustedBeforeEnoughFrames) {
  DegPerPxEstimator estimator(kTrueDegPerPx * 1.6);
  Fly(&estimator, 1.0, 11);  // below min_samples (12) fitted rows
  EXPECT_FALSE(estimator.trusted());
}

TEST(DegPerPxEstimatorTest, RestartForgetsTheFrames) {
  DegPerPxEstimator estimator(kTrueDegPerPx * 1.6);
  Fly(&estimator, 1.0, 300);
  ASSERT_TRUE(estimator.trusted());
  estimator.Restart(0.2);
  EXPECT_FALSE(estimator.trusted());
  EXPECT_DOUBLE_EQ(estimator.estimate_deg_per_px(), 0.2);
}

TEST(DegPerPxEstimatorTest, RefusesABadStartOrOptions) {
  EXPECT_THROW(DegPerPxEstimator(0.0), std::invalid_argument);
  EXPECT_THROW(DegPerPxEstimator(std::nan("")), std::invalid_argument);
  DegPerPxEstimatorOptions options;
  options.max_ratio = 1.0;
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("ratio"), std::string::npos) << error;
  EXPECT_THROW(DegPerPxEstimator(0.1, options), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
