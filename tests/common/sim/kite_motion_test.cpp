#include "common/sim/kite_motion.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <vector>

namespace kapfix {
namespace {

double Pendulum(double t, double a = 100, double period = 40, double tau = 400) {
  return a * std::sin(2 * std::numbers::pi * t / period) * std::exp(-t / tau);
}

KiteMotionOptions NoJitter() {
  KiteMotionOptions o;
  o.jitter_sigma_px = 0;
  return o;
}

TEST(KiteMotionTest, PendulumFormulaAtChosenFrames) {
  const KiteMotion kite(NoJitter());
  EXPECT_DOUBLE_EQ(kite.LineOfSight(0).x, 0.0);
  EXPECT_DOUBLE_EQ(kite.LineOfSight(10).x, 100 * std::exp(-10.0 / 400));   // sin = 1
  EXPECT_DOUBLE_EQ(kite.LineOfSight(30).x, -100 * std::exp(-30.0 / 400));  // sin = −1
  EXPECT_NEAR(kite.LineOfSight(20).x, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(kite.LineOfSight(5).x, Pendulum(5));
  EXPECT_DOUBLE_EQ(kite.LineOfSight(10).y, 0.0);
}

TEST(KiteMotionTest, PeakAmplitudeDecaysByEOverTau) {
  const KiteMotion kite(NoJitter());
  // Peaks one τ apart (t = 10 and 410, both at sin = 1).
  EXPECT_NEAR(kite.LineOfSight(410).x / kite.LineOfSight(10).x, std::exp(-1.0), 1e-12);
  double early = 0, late = 0;
  for (int t = 0; t < 40; ++t) early = std::max(early, std::abs(kite.LineOfSight(t).x));
  for (int t = 800; t < 840; ++t) late = std::max(late, std::abs(kite.LineOfSight(t).x));
  EXPECT_NEAR(late / early, std::exp(-2.0), 1e-3);
}

TEST(KiteMotionTest, JitterIsYOnlyWithTheConfiguredSigma) {
  KiteMotionOptions o;
  o.amplitude_px = 0;
  const KiteMotion kite(o);
  double sum = 0, sum2 = 0;
  constexpr int kN = 20000;
  for (int t = 0; t < kN; ++t) {
    const cv::Point2d p = kite.LineOfSight(t);
    ASSERT_EQ(p.x, 0.0);
    sum += p.y;
    sum2 += p.y * p.y;
  }
  const double mean = sum / kN;
  EXPECT_NEAR(mean, 0.0, 0.05);
  EXPECT_NEAR(std::sqrt(sum2 / kN - mean * mean), 2.0, 0.05);
}

TEST(KiteMotionTest, SameSeedGivesIdenticalPositions) {
  KiteMotionOptions o;
  o.gusts = true;
  const KiteMotion a(o), b(o);
  for (int t = 0; t < 400; ++t) {
    ASSERT_EQ(a.LineOfSight(t), b.LineOfSight(t)) << "frame " << t;
  }
}

TEST(KiteMotionTest, DifferentSeedGivesDifferentJitter) {
  KiteMotionOptions o;
  const KiteMotion a(o);
  o.seed = 2;
  const KiteMotion b(o);
  int differ = 0;
  for (int t = 0; t < 100; ++t) differ += a.LineOfSight(t).y != b.LineOfSight(t).y;
  EXPECT_GT(differ, 95);
}

TEST(KiteMotionTest, RandomAccessMatchesSequentialAccess) {
  KiteMotionOptions o;
  o.gusts = true;
  o.gust_rate_per_frame = 0.05;
  const KiteMotion kite(o);
  std::vector<cv::Point2d> forward;
  for (int t = 0; t < 400; ++t) forward.push_back(kite.LineOfSight(t));
  const KiteMotion fresh(o);
  for (int t = 399; t >= 0; t -= 7) {
    ASSERT_EQ(fresh.LineOfSight(t), forward[static_cast<std::size_t>(t)]) << "frame " << t;
  }
}

TEST(KiteMotionTest, GustSettingsDoNothingWhileGustsAreOff) {
  KiteMotionOptions o;
  o.gust_rate_per_frame = 0.5;
  o.gust_amplitude_px = 80;
  const KiteMotion stormy_settings(o);
  const KiteMotion plain(KiteMotionOptions{});
  EXPECT_TRUE(stormy_settings.Gusts(0, 10000).empty());
  for (int t = 0; t < 400; ++t) {
    ASSERT_EQ(stormy_settings.LineOfSight(t), plain.LineOfSight(t)) << "frame " << t;
  }
}

TEST(KiteMotionTest, GustsAddDampedSwingsFromTheirStartFrame) {
  KiteMotionOptions o = NoJitter();
  o.gusts = true;
  const KiteMotion kite(o);
  const std::vector<KiteGust> gusts = kite.Gusts(0, 399);
  ASSERT_GE(gusts.size(), 2u) << "seed 1 should raise gusts in 400 frames at 1/100";
  for (int t = 0; t < 400; ++t) {
    double expected = Pendulum(t);
    for (const KiteGust& g : gusts) {
      if (g.frame <= t) expected += g.amplitude_px * Pendulum(t - g.frame, 1.0);
    }
    ASSERT_NEAR(kite.LineOfSight(t).x, expected, 1e-9) << "frame " << t;
  }
  // Before the first gust the trajectory is the pure pendulum; after it, it is not.
  EXPECT_DOUBLE_EQ(kite.LineOfSight(gusts[0].frame).x, Pendulum(gusts[0].frame));
  EXPECT_GT(std::abs(kite.LineOfSight(gusts[0].frame + 5).x - Pendulum(gusts[0].frame + 5)), 1.0);
}

TEST(KiteMotionTest, GustsArriveAtTheConfiguredRateWithBoundedAmplitudes) {
  KiteMotionOptions o;
  o.gusts = true;
  o.gust_rate_per_frame = 0.01;
  o.gust_amplitude_px = 30;
  const KiteMotion kite(o);
  const std::vector<KiteGust> gusts = kite.Gusts(0, 99999);
  EXPECT_NEAR(static_cast<double>(gusts.size()), 1000.0, 100.0);
  int negative = 0;
  for (const KiteGust& g : gusts) {
    ASSERT_GE(std::abs(g.amplitude_px), 15.0);
    ASSERT_LE(std::abs(g.amplitude_px), 30.0);
    negative += g.amplitude_px < 0;
  }
  const double count = static_cast<double>(gusts.size());
  EXPECT_NEAR(negative, count / 2, 0.1 * count);
}

TEST(KiteMotionTest, FramesBeforeZeroAreAtRest) {
  const KiteMotion kite(KiteMotionOptions{});
  EXPECT_EQ(kite.LineOfSight(-5), cv::Point2d(0, 0));
}

TEST(KiteMotionTest, InvalidOptionsAreRejectedWithAReason) {
  KiteMotionOptions o;
  o.period_frames = 0;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("period"), std::string::npos) << error;
  EXPECT_THROW(KiteMotion{o}, std::invalid_argument);
  o = KiteMotionOptions{};
  o.gust_rate_per_frame = std::nan("");
  EXPECT_FALSE(o.IsValid(nullptr));
  EXPECT_TRUE(KiteMotionOptions{}.IsValid(nullptr));
}

// Frames between the swing's upward zero crossings, over `frames`.
std::vector<int> Periods(const KiteMotion& kite, int frames) {
  std::vector<int> periods;
  int last = -1;
  for (int t = 1; t < frames; ++t) {
    if (kite.LineOfSight(t - 1).x < 0 && kite.LineOfSight(t).x >= 0) {
      if (last >= 0) periods.push_back(t - last);
      last = t;
    }
  }
  return periods;
}

TEST(KiteMotionTest, PeriodDriftMakesThePeriodWander) {
  KiteMotionOptions o;
  o.decay_frames = 1e9;  // no decay: zero crossings all flight long
  o.jitter_sigma_px = 0;
  const std::vector<int> steady = Periods(KiteMotion(o), 1200);
  o.period_drift = 0.2;
  const std::vector<int> drifting = Periods(KiteMotion(o), 1200);
  ASSERT_FALSE(steady.empty());
  ASSERT_FALSE(drifting.empty());
  for (const int p : steady) EXPECT_NEAR(p, 40, 1);
  const auto [lo, hi] = std::minmax_element(drifting.begin(), drifting.end());
  EXPECT_LE(*lo, 36);
  EXPECT_GE(*hi, 44);
}

TEST(KiteMotionTest, SwayAddsASlowMotionOnBothAxesFromRest) {
  KiteMotionOptions o;
  o.amplitude_px = 0;
  o.jitter_sigma_px = 0;
  o.sway_amplitude_px = 20;
  const KiteMotion kite(o);
  EXPECT_EQ(kite.LineOfSight(0), cv::Point2d(0, 0));
  double largest_x = 0, largest_y = 0, largest_step = 0;
  for (int t = 1; t < 600; ++t) {
    largest_x = std::max(largest_x, std::abs(kite.LineOfSight(t).x));
    largest_y = std::max(largest_y, std::abs(kite.LineOfSight(t).y));
    largest_step =
        std::max(largest_step, std::abs(kite.LineOfSight(t).x - kite.LineOfSight(t - 1).x));
  }
  EXPECT_GT(largest_x, 15.0);
  EXPECT_GT(largest_y, 5.0);
  EXPECT_LT(largest_step, 1.0);  // slow: under a pixel per frame
}

TEST(KiteMotionTest, BroadbandGustsAreNotTheSwingsPeriod) {
  KiteMotionOptions o;
  o.amplitude_px = 0;
  o.jitter_sigma_px = 0;
  o.gusts = true;
  o.gust_model = KiteMotionOptions::GustModel::kBroadband;
  const KiteMotion kite(o);
  // An AR(2) fitted by least squares explains same-period gusts exactly; broadband
  // turbulence leaves a residual, and its power sits below the swing's frequency.
  double slow = 0, at_swing = 0;
  const int n = 2000;
  for (const auto& [f, sum] : {std::pair{1.0 / 400, &slow}, std::pair{1.0 / 40, &at_swing}}) {
    double re = 0, im = 0;
    for (int t = 0; t < n; ++t) {
      re += kite.LineOfSight(t).x * std::cos(2 * std::numbers::pi * f * t);
      im += kite.LineOfSight(t).x * std::sin(2 * std::numbers::pi * f * t);
    }
    *sum = std::hypot(re, im);
  }
  EXPECT_GT(slow, 3.0 * at_swing);
  EXPECT_TRUE(kite.Gusts(0, n).empty());  // no pendulum impulses in this model
}

TEST(KiteMotionTest, DriftAndSwayOutOfRangeAreRejected) {
  KiteMotionOptions o;
  o.period_drift = 0.7;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("drift"), std::string::npos);
  o.period_drift = 0;
  o.sway_amplitude_px = -1;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("sway"), std::string::npos);
}

}  // namespace
}  // namespace kapfix
