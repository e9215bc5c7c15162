#include "common/sim/kite_motion.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
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

KiteMotionOptions BroadbandOnly() {
  KiteMotionOptions o;
  o.amplitude_px = 0;
  o.jitter_sigma_px = 0;
  o.gusts = true;
  o.gust_model = KiteMotionOptions::GustModel::kBroadband;
  return o;
}

// |Σ s(t)·hann(t)·e^(−2πift)| over t in [0, n): a series' amplitude at frequency f.
double AmplitudeAt(const std::function<double(int)>& s, int n, double f) {
  double re = 0, im = 0;
  for (int t = 0; t < n; ++t) {
    const double w = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * t / (n - 1));
    re += w * s(t) * std::cos(2 * std::numbers::pi * f * t);
    im += w * s(t) * std::sin(2 * std::numbers::pi * f * t);
  }
  return std::hypot(re, im);
}

// The wind is a force on the rig, not a displacement of the view: its spectrum is not the
// swing's (a low-pass with no peak at the swing's frequency), and the view follows it through
// the pendulum: slow pushes pass (gain ~1 at 1/400 cycles/frame), fast ones are low-passed by
// the rig's inertia (gain (f₀/f)² ≈ 1/24 at 1/8 cycles/frame for the 40-frame swing; the
// old model added the turbulence to the view with gain 1 at every frequency).
TEST(KiteMotionTest, BroadbandWindIsAForceTheRigsInertiaLowPasses) {
  KiteMotionOptions o = BroadbandOnly();
  o.gust_rate_per_frame = 0;  // turbulence alone
  const KiteMotion kite(o);
  const int n = 4000;
  const auto wind = [&kite](int t) { return kite.Wind(t); };
  const auto view = [&kite](int t) { return kite.LineOfSight(t).x; };
  const double slow = 1.0 / 400, swing = 1.0 / 40, fast = 1.0 / 8;
  EXPECT_LT(AmplitudeAt(wind, n, swing), AmplitudeAt(wind, n, slow)) << "no peak at the swing";
  const double slow_gain = AmplitudeAt(view, n, slow) / AmplitudeAt(wind, n, slow);
  const double fast_gain = AmplitudeAt(view, n, fast) / AmplitudeAt(wind, n, fast);
  EXPECT_GT(slow_gain, 0.7);
  EXPECT_LT(slow_gain, 1.5);
  EXPECT_LT(fast_gain, 0.1);
  EXPECT_TRUE(kite.Gusts(0, n).empty());  // no pendulum impulses in this model
}

TEST(KiteMotionTest, BroadbandResponseHasTheConfiguredRms) {
  KiteMotionOptions o = BroadbandOnly();
  o.gust_rate_per_frame = 0;
  const KiteMotion kite(o);
  double sum_sq = 0;
  const int n = 8000;
  for (int t = 0; t < n; ++t) sum_sq += std::pow(kite.LineOfSight(t).x, 2);
  const double rms = std::sqrt(sum_sq / n);
  EXPECT_GT(rms, 0.6 * 0.5 * o.gust_amplitude_px);
  EXPECT_LT(rms, 1.5 * 0.5 * o.gust_amplitude_px);
}

// Integrated frame by frame, the response is still a pure function of (seed, frame): asked out
// of order, by a copy, or by another instance, the same frame gives the same view.
TEST(KiteMotionTest, BroadbandResponseIsTheSameInAnyOrder) {
  const KiteMotion a(BroadbandOnly());
  const double late = a.LineOfSight(700).x;
  const double early = a.LineOfSight(100).x;
  const KiteMotion b(BroadbandOnly());
  EXPECT_EQ(b.LineOfSight(100).x, early);
  EXPECT_EQ(b.LineOfSight(700).x, late);
  const KiteMotion copy = a;  // NOLINT(performance-unnecessary-copy-initialization)
  EXPECT_EQ(copy.LineOfSight(701).x, b.LineOfSight(701).x);
  KiteMotionOptions other = BroadbandOnly();
  other.seed = 2;
  EXPECT_NE(KiteMotion(other).LineOfSight(100).x, early);
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
