#include "common/control/swing_predictor.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "common/sim/sim_random.hpp"

namespace kapfix {
namespace {

using Forecaster = SwingPredictor::Forecaster;

constexpr double kOmega = 2 * std::numbers::pi / 40;  // SPEC §3: T = 40 frames

// 100 px swing around 20 px, decaying with τ = 400 frames.
double Swing(int t) { return 20 + 100 * std::sin(kOmega * t) * std::exp(-t / 400.0); }

// Feeds samples 0 … frames − 1 of `measured` and returns the RMS error of the forecasts
// against `truth` two frames later, over the forecasts for samples ≥ from.
double ForecastRms(SwingPredictor& predictor, const std::function<double(int)>& measured,
                   const std::function<double(int)>& truth, int frames, int from) {
  const int lead = predictor.options().lead_frames;
  std::vector<double> forecast(static_cast<std::size_t>(frames + lead), std::nan(""));
  double sum_sq = 0;
  int count = 0;
  for (int t = 0; t < frames; ++t) {
    if (t >= from) {
      EXPECT_TRUE(std::isfinite(forecast[t])) << "no forecast for sample " << t;
      sum_sq += (forecast[t] - truth(t)) * (forecast[t] - truth(t));
      ++count;
    }
    predictor.Add(measured(t));
    if (const auto f = predictor.Predict()) forecast[t + lead] = *f;
  }
  return std::sqrt(sum_sq / count);
}

TEST(SwingPredictorTest, PredictsAPureSwingTwoFramesAhead) {
  SwingPredictor predictor;  // lead 2
  for (int t = 0; t < 40; ++t) predictor.Add(Swing(t));
  EXPECT_EQ(predictor.chosen(), Forecaster::kModel);
  ASSERT_TRUE(predictor.Predict().has_value());
  EXPECT_NEAR(*predictor.Predict(), Swing(41), 1e-6);
}

TEST(SwingPredictorTest, PredictsANoisySwingWithinAFewTenthsOfAPixel) {
  SwingPredictor predictor;
  const auto noisy = [](int t) { return Swing(t) + 0.2 * SimGaussian(3, 0, t); };
  // Persistence would be off by up to 2 · 15.7 px; the raw AR(2) recurrence amplifies the
  // 0.2 px noise ×3.5, to 0.7 px. The state fit averages it.
  EXPECT_LT(ForecastRms(predictor, noisy, Swing, 300, 40), 0.4);
}

// The AR(2) model's poles: radius and period [frames] of x_t = a1·x_{t−1} + a2·x_{t−2} + c.
struct Poles {
  double radius, period;
};
Poles PolesOf(const std::vector<double>& coefficients) {
  const double a1 = coefficients.at(0), a2 = coefficients.at(1);
  if (a1 * a1 + 4 * a2 >= 0) return {std::nan(""), std::nan("")};  // real poles: no swing
  const double radius = std::sqrt(-a2);
  return {radius, 2 * std::numbers::pi / std::acos(a1 / (2 * radius))};
}

double MedianOf(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? std::nan("") : v[v.size() / 2];
}

TEST(SwingPredictorTest, FitsALightlyDampedSwingUnbiasedUnderTwoPixelsOfNoise) {
  // Pole radius 0.9975, period 40 frames, σ = 2 px of white measurement noise. Least
  // squares shrinks the poles towards the origin (radius ~0.89, periods wandering from ~40
  // to several hundred frames); the model must not.
  SwingPredictor predictor;  // window 80 frames
  std::vector<double> radii, periods;
  double worst_radius = 0, worst_period = 0;
  for (int t = 0; t < 300; ++t) {  // amplitude 100 → 47 px
    predictor.Add(20 + 100 * std::pow(0.9975, t) * std::sin(kOmega * t) + 2 * SimGaussian(7, 0, t));
    if (t < 80) continue;
    ASSERT_TRUE(predictor.has_model()) << "sample " << t;
    const Poles poles = PolesOf(predictor.coefficients());
    ASSERT_TRUE(std::isfinite(poles.radius)) << "no oscillating poles at sample " << t;
    radii.push_back(poles.radius);
    periods.push_back(poles.period);
    worst_radius = std::max(worst_radius, std::abs(poles.radius - 0.9975));
    worst_period = std::max(worst_period, std::abs(poles.period - 40));
  }
  EXPECT_NEAR(MedianOf(radii), 0.9975, 0.005);
  EXPECT_NEAR(MedianOf(periods), 40.0, 1.0);
  EXPECT_LT(worst_radius, 0.03);
  EXPECT_LT(worst_period, 5.0);
}

TEST(SwingPredictorTest, ModelIsScoredOnTheForecastItActsOn) {
  // Scored on raw samples, the model's two-frame forecast would amplify σ = 1 px of noise
  // ×3.5; Predict() forecasts from the smoothed state. The score must be the error of what
  // Predict() returned: within 25 % of the RMS of those forecasts against the samples.
  SwingPredictor predictor;
  const int lead = predictor.options().lead_frames;
  const int span = predictor.options().skill_frames;
  std::vector<double> samples, forecasts(1000, std::nan(""));
  for (int t = 0; t < 400; ++t) {
    samples.push_back(Swing(t) + SimGaussian(8, 0, t));
    predictor.Add(samples.back());
    if (const auto f = predictor.Predict()) forecasts[t + lead] = *f;
  }
  ASSERT_EQ(predictor.chosen(), Forecaster::kModel);
  double sum_sq = 0;
  for (int t = 400 - span; t < 400; ++t) {
    ASSERT_TRUE(std::isfinite(forecasts[t]));
    sum_sq += (samples[t] - forecasts[t]) * (samples[t] - forecasts[t]);
  }
  const double acted_rms = std::sqrt(sum_sq / span);
  EXPECT_NEAR(predictor.skill_rms(Forecaster::kModel), acted_rms, 0.25 * acted_rms);
}

TEST(SwingPredictorTest, RecoversTwoSamplesAfterAGust) {
  SwingPredictor predictor;
  // A gust at sample 60: a second swing of the same period and decay starts from rest
  // (SPEC §3).
  const auto gusty = [](int t) {
    return Swing(t) +
           (t >= 60 ? 30 * std::sin(kOmega * (t - 60)) * std::exp(-(t - 60) / 400.0) : 0.0);
  };
  for (int t = 0; t < 62; ++t) predictor.Add(gusty(t));
  EXPECT_EQ(predictor.jumps(), 1);
  // The forecast made after the gust's first sample already follows the new swing.
  EXPECT_NEAR(*predictor.Predict(), gusty(63), 1e-6);
}

// The RMS error of the forecast acted on lead frames ahead (persistence's included) against
// the samples themselves, over samples from … frames − 1.
double ActedForecastRms(SwingPredictor& predictor, const std::function<double(int)>& measured,
                        int frames, int from) {
  const int lead = predictor.options().lead_frames;
  std::vector<double> forecast(static_cast<std::size_t>(frames + lead), std::nan(""));
  double sum_sq = 0;
  int count = 0;
  for (int t = 0; t < frames; ++t) {
    if (t >= from && std::isfinite(forecast[t])) {
      sum_sq += (forecast[t] - measured(t)) * (forecast[t] - measured(t));
      ++count;
    }
    predictor.Add(measured(t));
    if (const auto f = predictor.Forecast(lead)) forecast[t + lead] = *f;
  }
  return std::sqrt(sum_sq / count);
}

// A slow sway of the line under the swing: 7.3 swing periods, as the simulated world's.
double Sway(int t, double amplitude_px, double periods) {
  return amplitude_px * std::sin(kOmega * t / periods + 1.0);
}

TEST(SwingPredictorTest, ASlowSwayUnderTheSwingDoesNotSpoilTheForecast) {
  // The sway moves the level the swing is around. σ = 0.5 px of noise, as on the views
  // reconstructed in a simulated flight. The state filter follows much of the sway by itself;
  // the drifting offset must still not make it worse.
  const auto truth = [](int t) { return Swing(t) + Sway(t, 20, 7.3); };
  const auto noisy = [&](int t) { return truth(t) + 0.5 * SimGaussian(11, 0, t); };
  const auto calm = [](int t) { return Swing(t) + 0.5 * SimGaussian(11, 0, t); };
  SwingPredictor swaying;
  const double with_sway = ForecastRms(swaying, noisy, truth, 600, 100);
  SwingPredictor still;
  const double without_sway = ForecastRms(still, calm, Swing, 600, 100);
  SwingPredictorOptions fixed_offset;
  fixed_offset.drifting_offset = false;
  SwingPredictor without(fixed_offset);
  const double without_drift = ForecastRms(without, noisy, truth, 600, 100);
  EXPECT_LT(with_sway, 1.6 * without_sway);
  EXPECT_LT(with_sway, without_drift);
}

// A swing the wind pushes a little every frame (white force, as a broadband wind's fast
// part) seen through σ = 1 px of noise, in the same units.
double WindPushed(int t) {
  static std::vector<double> x = {0.0, 0.0};
  while (static_cast<int>(x.size()) <= t) {
    const auto n = static_cast<int>(x.size());
    const double a1 = 2 * 0.9975 * std::cos(kOmega), a2 = -0.9975 * 0.9975;
    x.push_back(a1 * x[n - 1] + a2 * x[n - 2] + 0.5 + SimGaussian(21, 0, n));
  }
  return x[static_cast<std::size_t>(t)];
}

TEST(SwingPredictorTest, AWindPushedSwingIsForecastFromAFilteredState) {
  // A state fitted through the model as if nothing pushed the swing (a tiny process noise)
  // trails every push; the filter weighs pushes against the measurement's noise.
  const auto measured = [](int t) { return WindPushed(t) + SimGaussian(22, 0, t); };
  SwingPredictor filtered;
  SwingPredictorOptions rigid_options;
  rigid_options.state_noise_ratio = 1e-4;
  SwingPredictor rigid(rigid_options);
  const double filtered_rms = ActedForecastRms(filtered, measured, 600, 100);
  const double rigid_rms = ActedForecastRms(rigid, measured, 600, 100);
  EXPECT_LT(filtered_rms, 0.8 * rigid_rms) << filtered_rms << " px against " << rigid_rms;
}

TEST(SwingPredictorTest, AnUndriftingSwingIsForecastAsWellAsWithAFixedOffset) {
  // The drift is one more unknown: where there is none it must cost the forecast little.
  const auto noisy = [](int t) { return Swing(t) + 0.3 * SimGaussian(13, 0, t); };
  SwingPredictor drifting;
  SwingPredictorOptions fixed_offset;
  fixed_offset.drifting_offset = false;
  SwingPredictor fixed(fixed_offset);
  EXPECT_LT(ForecastRms(drifting, noisy, Swing, 600, 100),
            1.1 * ForecastRms(fixed, noisy, Swing, 600, 100));
}

TEST(SwingPredictorTest, JitterOnASlowSwayIsForecastNearItsOwnSpread) {
  // The tilt axis: σ = 2 px of white jitter around a 10 px sway of 11.1 swing periods. The
  // best forecast is the sway, off by the jitter's 2 px; persistence is off by 2.8. Without a
  // drifting offset the model did no better than persistence.
  const auto measured = [](int t) { return Sway(t, 10, 11.1) + 2 * SimGaussian(12, 0, t); };
  SwingPredictor predictor;
  EXPECT_LT(ActedForecastRms(predictor, measured, 600, 100), 2.35);
}

TEST(SwingPredictorTest, WhiteJitterIsForecastAsItsMean) {
  SwingPredictor predictor;
  for (int t = 0; t < 200; ++t) predictor.Add(5 + 2 * SimGaussian(4, 0, t));
  EXPECT_EQ(predictor.chosen(), Forecaster::kModel);
  ASSERT_TRUE(predictor.Predict().has_value());
  EXPECT_NEAR(*predictor.Predict(), 5.0, 0.7);
}

TEST(SwingPredictorTest, ConstantSeriesFallsBackToPersistence) {
  SwingPredictor predictor;
  for (int t = 0; t < 50; ++t) predictor.Add(3.0);
  EXPECT_FALSE(predictor.has_model());  // no swing to fit
  EXPECT_EQ(predictor.chosen(), Forecaster::kPersistence);
  EXPECT_FALSE(predictor.Predict().has_value());
}

TEST(SwingPredictorTest, LargeFirstStepIsExtrapolated) {
  SwingPredictor predictor;
  predictor.Add(0);
  predictor.Add(10);
  EXPECT_EQ(predictor.chosen(), Forecaster::kLinear);
  EXPECT_DOUBLE_EQ(predictor.Predict().value_or(0), 30.0);  // 10 + 2 · 10
}

TEST(SwingPredictorTest, SmallFirstStepIsNotExtrapolated) {
  SwingPredictor predictor;
  predictor.Add(0);
  predictor.Add(3);  // below linear_prior_min_step: may be jitter
  EXPECT_FALSE(predictor.Predict().has_value());
}

TEST(SwingPredictorTest, LinearLosesToPersistenceOnJitter) {
  SwingPredictorOptions options;
  options.window_frames = 400;  // no model in the first 20 samples: linear vs persistence only
  options.order = 8;
  SwingPredictor predictor(options);
  for (int t = 0; t < 20; ++t) predictor.Add(10 * SimGaussian(5, 0, t));
  EXPECT_FALSE(predictor.has_model());
  EXPECT_EQ(predictor.chosen(), Forecaster::kPersistence);
}

TEST(SwingPredictorTest, CoastsOverAShortGapThenGivesUp) {
  SwingPredictor predictor;  // max_coast_frames 3
  for (int t = 0; t < 40; ++t) predictor.Add(Swing(t));
  for (int t = 40; t < 43; ++t) {
    EXPECT_TRUE(predictor.AddMissing()) << "sample " << t;
    EXPECT_NEAR(*predictor.Predict(), Swing(t + 2), 1e-6);
  }
  EXPECT_FALSE(predictor.AddMissing());
  EXPECT_EQ(predictor.samples(), 0);
  EXPECT_FALSE(predictor.Predict().has_value());
}

TEST(SwingPredictorTest, RejectsAWindowTooShortForTheOrder) {
  SwingPredictorOptions options;
  options.order = 8;
  options.window_frames = 30;
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("window"), std::string::npos);
  EXPECT_THROW(SwingPredictor{options}, std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
