#include "common/control/deg_per_px_estimator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

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
// measured displacement d = swing − angle / deg_per_px + noise. A servo with `play_deg` of
// backlash shows the output angle, which lags the command by half the play in the direction
// it last moved; the estimator is told the command, as the loop is.
void Fly(DegPerPxEstimator* estimator, double noise_px, int frames, double play_deg = 0) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, noise_px);
  std::uniform_real_distribution<double> step(-2.0, 2.0);
  double angle = 0, output = 0;
  for (int t = 0; t < frames; ++t) {
    if (t % 10 == 0) angle = step(rng);
    output = std::clamp(output, angle - play_deg / 2, angle + play_deg / 2);
    estimator->Add(angle, Swing(t) - output / kTrueDegPerPx + noise(rng));
  }
}

// A loop that locks on at frame 10 (a jump of the servo onto the swing) and then holds the
// view: the servo follows the swing with a smooth forecast error of ~0.7 px, and the view
// shows what is left plus `noise_px` of measurement noise. Returns the estimate [deg/px] at
// each frame from `from` on.
std::vector<double> LockOnAndHold(DegPerPxEstimator* estimator, double noise_px, int frames,
                                  int from) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, noise_px), wander(0.0, 0.3);
  double forecast_error = 0;
  std::vector<double> estimates;
  for (int t = 0; t < frames; ++t) {
    forecast_error = 0.9 * forecast_error + wander(rng);
    const double angle = t < 10 ? 0.0 : (Swing(t) + forecast_error) * kTrueDegPerPx;
    estimator->Add(angle, Swing(t) - angle / kTrueDegPerPx + noise(rng));
    if (t >= from) estimates.push_back(estimator->estimate_deg_per_px());
  }
  return estimates;
}

TEST(DegPerPxEstimatorTest, FindsTheTrueDegPerPxUnderOnePixelOfNoise) {
  for (const double error : {0.6, 1.3, 1.6}) {
    DegPerPxEstimator estimator(kTrueDegPerPx * error);
    Fly(&estimator, 1.0, 500);
    EXPECT_NEAR(estimator.estimate_deg_per_px() / kTrueDegPerPx, 1.0, 0.03) << error;
    EXPECT_TRUE(estimator.trusted()) << error << ": σ " << estimator.relative_sigma();
  }
}

TEST(DegPerPxEstimatorTest, ReportsItsUncertaintyHonestlyUnderTwoPixelsOfNoise) {
  // Each segment's swing model and play cost information: at 2 px over 500 frames of these
  // moves the estimate is not yet acted on, and its σ covers its error.
  for (const double error : {0.6, 1.3, 1.6}) {
    DegPerPxEstimator estimator(kTrueDegPerPx * error);
    Fly(&estimator, 2.0, 500);
    const double sigma = estimator.relative_sigma();
    EXPECT_LT(sigma, 0.1) << error;
    EXPECT_NEAR(estimator.estimate_deg_per_px() / kTrueDegPerPx, 1.0, 2.5 * sigma) << error;
  }
}

TEST(DegPerPxEstimatorTest, FitsTheServosPlay) {
  // 0.2° of play is 2 px of view: fitted as a calibration error it biased the estimate by 9 %
  // (trusted, σ 0.5 %); the same frames with the play modelled end within 2 %.
  DegPerPxEstimator estimator(kTrueDegPerPx * 1.3);
  Fly(&estimator, 0.2, 500, 0.2);
  EXPECT_NEAR(estimator.estimate_deg_per_px() / kTrueDegPerPx, 1.0, 0.02);
  EXPECT_TRUE(estimator.trusted()) << "σ " << estimator.relative_sigma();
}

TEST(DegPerPxEstimatorTest, WithoutThePlayModelTheSameServoBiasesTheEstimate) {
  // The counterpart of FitsTheServosPlay: shows that the play is what the model removes.
  DegPerPxEstimatorOptions options;
  options.backlash = false;
  DegPerPxEstimator estimator(kTrueDegPerPx * 1.3, options);
  Fly(&estimator, 0.2, 500, 0.2);
  EXPECT_GT(std::abs(estimator.estimate_deg_per_px() / kTrueDegPerPx - 1.0), 0.05);
}

TEST(DegPerPxEstimatorTest, AHeldViewUnderTwoPixelsOfNoiseDoesNotMoveTheEstimate) {
  // Once the loop holds the view, the servo only follows the swing: any θ explains the
  // frames up to noise, whose slope over a long hold used to carry the estimate off (an
  // estimate fitted on the hold alone ends at the span's edge).
  DegPerPxEstimator estimator(kTrueDegPerPx * 1.3);
  const std::vector<double> estimates = LockOnAndHold(&estimator, 2.0, 500, 100);
  const double at_hold = estimates.front();
  EXPECT_NEAR(at_hold / kTrueDegPerPx, 1.0, 0.1);  // the lock-on's jump alone, at 2 px
  for (const double e : estimates) EXPECT_NEAR(e / at_hold, 1.0, 0.01);
}

TEST(DegPerPxEstimatorTest, AHeldViewAtTheSimulatedMatchersNoiseKeepsItTrustedAndRight) {
  DegPerPxEstimator estimator(kTrueDegPerPx * 1.3);
  const std::vector<double> estimates = LockOnAndHold(&estimator, 0.2, 500, 50);
  for (const double e : estimates) EXPECT_NEAR(e / kTrueDegPerPx, 1.0, 0.02);
  EXPECT_TRUE(estimator.trusted()) << "σ " << estimator.relative_sigma();
}

TEST(DegPerPxEstimatorTest, NoiseFreeFramesDoNotMakeAWrongEstimateCertain) {
  // Without noise the frames are fitted exactly by many θ: a residual of zero must not read
  // as σ = 0 (a matcher always has some noise). Without the noise floor this loop's estimate
  // was 2.4× off and trusted.
  // A noise-free P loop (gain 1, the command acting two frames later) on a pure swing.
  DegPerPxEstimator estimator(kTrueDegPerPx);
  std::vector<double> angles(302, 0.0);
  for (int t = 0; t < 300; ++t) {
    const double swing = 100 * std::sin(2 * std::numbers::pi * t / 40.0);
    const double d = swing - angles[t] / kTrueDegPerPx;
    estimator.Add(angles[t], d);
    angles[t + 2] = angles[t] + d * kTrueDegPerPx;
    if (estimator.trusted()) {
      EXPECT_NEAR(estimator.estimate_deg_per_px() / kTrueDegPerPx, 1.0, 0.01) << "frame " << t;
    }
  }
}

TEST(DegPerPxEstimatorTest, ALowExcitationStretchDoesNotMoveATrustedEstimate) {
  DegPerPxEstimator estimator(kTrueDegPerPx * 1.3);
  Fly(&estimator, 1.0, 500);
  ASSERT_TRUE(estimator.trusted());
  const double trusted = estimator.estimate_deg_per_px();
  // 400 frames in which the servo cancels the swing exactly: no information on θ.
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (int t = 500; t < 900; ++t) {
    estimator.Add(Swing(t) * kTrueDegPerPx, noise(rng));
    EXPECT_NEAR(estimator.estimate_deg_per_px() / trusted, 1.0, 0.01) << "frame " << t;
  }
  EXPECT_TRUE(estimator.trusted()) << "σ " << estimator.relative_sigma();
}

TEST(DegPerPxEstimatorTest, AFrameSeenThroughAnotherAngleIsNotFitted) {
  // Under latency jitter the loop may believe the previous command still in effect when the
  // new one already was: the frame was seen through an angle a whole step (up to 4°, 40 px)
  // away. Here at every fifth step: unscreened, these frames moved the estimate by 3.6 %.
  // (Known limit: at every other step the screened estimate is still 1.5 % off.)
  DegPerPxEstimator clean(kTrueDegPerPx * 1.3), wrong(kTrueDegPerPx * 1.3);
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.2);
  std::uniform_real_distribution<double> step(-2.0, 2.0);
  double angle = 0, previous = 0;
  for (int t = 0; t < 500; ++t) {
    if (t % 10 == 0) {
      previous = angle;
      angle = step(rng);
    }
    const double d = Swing(t) - angle / kTrueDegPerPx + noise(rng);
    clean.Add(angle, d);
    wrong.Add(t % 50 == 0 ? previous : angle, d);
  }
  ASSERT_TRUE(clean.trusted());
  EXPECT_NEAR(wrong.estimate_deg_per_px() / clean.estimate_deg_per_px(), 1.0, 0.01);
  EXPECT_TRUE(wrong.trusted()) << "σ " << wrong.relative_sigma();
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
  Fly(&estimator, 1.0, 11);  // 9 fitted rows, below min_samples (10)
  EXPECT_FALSE(estimator.trusted());
}

TEST(DegPerPxEstimatorTest, IsTrustedOnTheLockOnsFirstFramesNotAtTheNextRefit) {
  // A calibration ×0.6 costs most on lock-on, so until its first trusted fit the estimate is
  // refitted every frame, not every refit_every (5): trust comes on the first frame it can.
  for (const double error : {0.6, 1.6}) {
    DegPerPxEstimator estimator(kTrueDegPerPx * error);
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0.0, 0.2);
    std::uniform_real_distribution<double> step(-2.0, 2.0);
    int trusted_at = -1;
    double angle = 0;
    for (int t = 0; t < 40 && trusted_at < 0; ++t) {
      if (t % 2 == 0) angle = step(rng);  // the lock-on's corrections
      estimator.Add(angle, Swing(t) - angle / kTrueDegPerPx + noise(rng));
      if (estimator.trusted()) trusted_at = t;
    }
    ASSERT_GE(trusted_at, 0) << error;
    // Fitted only every 5 frames (frames 4, 9, 14…) it would be trusted at 14 at the earliest.
    EXPECT_LE(trusted_at, 13) << error;
    EXPECT_NEAR(estimator.estimate_deg_per_px() / kTrueDegPerPx, 1.0, 0.05) << error;
  }
}

TEST(DegPerPxEstimatorTest, RestartForgetsTheFrames) {
  DegPerPxEstimator estimator(kTrueDegPerPx * 1.6);
  Fly(&estimator, 1.0, 500);
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
  options = {};
  options.segment_frames = options.window_frames + 1;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("segments"), std::string::npos) << error;
  options = {};
  options.segment_max_relative_sigma = 0;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("segment"), std::string::npos) << error;
}

}  // namespace
}  // namespace kapfix
