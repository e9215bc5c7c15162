#include "common/sim/kite_motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "common/sim/sim_random.hpp"

namespace kapfix {
namespace {

// Independent random streams of one seed.
constexpr std::uint64_t kJitterStream = 0x6b6974654a;  // "kiteJ"
constexpr std::uint64_t kGustStream = 0x6b69746547;    // "kiteG"
constexpr std::uint64_t kGustSizeStream = 0x6b69746553;
constexpr std::uint64_t kPhaseStream = 0x6b69746550;     // drift, sway, turbulence phases
constexpr std::uint64_t kStepGustStream = 0x6b69746554;  // broadband step gusts

constexpr double kDriftPeriodFrames = 600;       // [frames] how slowly the swing period wanders
constexpr double kSwayPeriodX = 7.3;             // [swing periods] the slow sway along x
constexpr double kSwayPeriodY = 11.1;            // [swing periods] and along y
constexpr int kTurbulenceComponents = 32;        // sinusoids of the spectral representation
constexpr double kTurbulenceCorner = 1.0 / 150;  // [cycles/frame] Dryden-like corner
constexpr double kStepRiseFrames = 8;            // [frames] a step gust's 1 − cos rise
constexpr double kStepDecayFrames = 150;         // [frames] how fast the line drifts back

// Gusts older than this many τ contribute less than e^−40 of their amplitude.
constexpr double kGustHorizonTaus = 40.0;

bool Finite(double v) { return std::isfinite(v); }

}  // namespace

bool KiteMotionOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (!Finite(amplitude_px) || amplitude_px < 0) {
    return fail("kite amplitude must be ≥ 0 px, got " + std::to_string(amplitude_px));
  }
  if (!Finite(period_frames) || period_frames <= 0) {
    return fail("kite period must be > 0 frames, got " + std::to_string(period_frames));
  }
  if (!Finite(decay_frames) || decay_frames <= 0) {
    return fail("kite decay τ must be > 0 frames, got " + std::to_string(decay_frames));
  }
  if (!Finite(jitter_sigma_px) || jitter_sigma_px < 0) {
    return fail("kite jitter σ must be ≥ 0 px, got " + std::to_string(jitter_sigma_px));
  }
  if (!(gust_rate_per_frame >= 0 && gust_rate_per_frame <= 1)) {
    return fail("gust rate must be in [0, 1] per frame, got " +
                std::to_string(gust_rate_per_frame));
  }
  if (!Finite(gust_amplitude_px) || gust_amplitude_px < 0) {
    return fail("gust amplitude must be ≥ 0 px, got " + std::to_string(gust_amplitude_px));
  }
  if (!(period_drift >= 0 && period_drift <= 0.5)) {
    return fail("period drift must be in [0, 0.5], got " + std::to_string(period_drift));
  }
  if (!Finite(sway_amplitude_px) || sway_amplitude_px < 0) {
    return fail("sway amplitude must be ≥ 0 px, got " + std::to_string(sway_amplitude_px));
  }
  return true;
}

KiteMotion::KiteMotion(KiteMotionOptions options) : options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument("KiteMotion: " + error);
}

double KiteMotion::GustAmplitude(int frame) const {
  if (!options_.gusts || frame < 1) return 0.0;
  if (SimUniform(options_.seed, kGustStream, frame) >= options_.gust_rate_per_frame) return 0.0;
  const double u = SimUniform(options_.seed, kGustSizeStream, frame);  // [0, 1)
  // Low half decides the sign, the rest the size in [½, 1): no negligible gusts.
  const double size = 0.5 + std::fmod(2.0 * u, 1.0) * 0.5;
  return (u < 0.5 ? -1.0 : 1.0) * size * options_.gust_amplitude_px;
}

std::vector<KiteGust> KiteMotion::Gusts(int first_frame, int last_frame) const {
  std::vector<KiteGust> gusts;
  if (!options_.gusts || options_.gust_model != KiteMotionOptions::GustModel::kPeriodic) {
    return gusts;
  }
  for (int g = std::max(first_frame, 1); g <= last_frame; ++g) {
    const double a = GustAmplitude(g);
    if (a != 0.0) gusts.push_back({g, a});
  }
  return gusts;
}

double KiteMotion::Phase(double t) const {
  const double omega = 2.0 * std::numbers::pi / options_.period_frames;
  if (options_.period_drift == 0.0) return omega * t;
  // ω(t) = ω·(1 + F·sin(νt + φ)) integrates to ω·(t − F/ν·(cos(νt + φ) − cos φ)).
  const double nu = 2.0 * std::numbers::pi / kDriftPeriodFrames;
  const double phi = 2.0 * std::numbers::pi * SimUniform(options_.seed, kPhaseStream, 0);
  return omega * (t - options_.period_drift / nu * (std::cos(nu * t + phi) - std::cos(phi)));
}

double KiteMotion::Broadband(int frame) const {
  const double t = frame;
  const double two_pi = 2.0 * std::numbers::pi;
  // Spectral representation of a low-pass turbulence: log-spaced frequencies from 1/3000 to
  // 1/6 cycles per frame, each with the power S(f)·Δf of S(f) ∝ 1/(1 + (f/fc)²), random
  // phases. Normalised to RMS ½·gust_amplitude.
  const double f_lo = 1.0 / 3000, f_hi = 1.0 / 6;
  const double ratio = std::pow(f_hi / f_lo, 1.0 / (kTurbulenceComponents - 1));
  double power_sum = 0, x = 0;
  for (int k = 0; k < kTurbulenceComponents; ++k) {
    const double f = f_lo * std::pow(ratio, k);
    const double df = f * (ratio - 1.0);
    const double power = df / (1.0 + (f / kTurbulenceCorner) * (f / kTurbulenceCorner));
    power_sum += power;
    const double phase = two_pi * SimUniform(options_.seed, kPhaseStream, 10 + k);
    x += std::sqrt(2.0 * power) * std::sin(two_pi * f * t + phase);
  }
  x *= 0.5 * options_.gust_amplitude_px / std::sqrt(power_sum);
  // Step gusts: a smooth push of the line that then drifts back.
  // Ten decay times: what is left (< 5·10⁻⁵ of the step) is far below a pixel.
  const int horizon = static_cast<int>(std::ceil(10.0 * kStepDecayFrames));
  const double rate = options_.gust_rate_per_frame / 4.0;
  for (int g = std::max(1, frame - horizon); g <= frame; ++g) {
    const double u = SimUniform(options_.seed, kStepGustStream, g);
    if (u >= rate) continue;
    const double size = (u / rate < 0.5 ? -1.0 : 1.0) *
                        (0.5 + 0.5 * SimUniform(options_.seed, kStepGustStream + 1, g));
    const double age = t - g;
    const double rise = age >= kStepRiseFrames
                            ? 1.0
                            : 0.5 * (1.0 - std::cos(std::numbers::pi * age / kStepRiseFrames));
    x += size * options_.gust_amplitude_px * rise * std::exp(-age / kStepDecayFrames);
  }
  return x;
}

cv::Point2d KiteMotion::LineOfSight(int frame) const {
  if (frame < 0) return {0.0, 0.0};
  const double t = frame;
  const double tau = options_.decay_frames;
  const double phase = Phase(t);
  double x = options_.amplitude_px * std::sin(phase) * std::exp(-t / tau);
  if (options_.gusts && options_.gust_model == KiteMotionOptions::GustModel::kPeriodic) {
    const double horizon = std::min(t, std::ceil(kGustHorizonTaus * tau));
    for (int g = frame - static_cast<int>(horizon); g <= frame; ++g) {
      const double a = GustAmplitude(g);
      if (a == 0.0) continue;
      const double age = t - g;
      x += a * std::sin(phase - Phase(g)) * std::exp(-age / tau);
    }
  }
  if (options_.gusts && options_.gust_model == KiteMotionOptions::GustModel::kBroadband) {
    x += Broadband(frame);
  }
  double y = options_.jitter_sigma_px * SimGaussian(options_.seed, kJitterStream, frame);
  if (options_.sway_amplitude_px > 0.0) {
    const double two_pi = 2.0 * std::numbers::pi;
    const double T = options_.period_frames;
    const double px = two_pi * SimUniform(options_.seed, kPhaseStream, 1);
    const double py = two_pi * SimUniform(options_.seed, kPhaseStream, 2);
    // Starts at rest (sin − sin φ), so frame 0's view is the pendulum's alone.
    x += options_.sway_amplitude_px *
         (std::sin(two_pi * t / (kSwayPeriodX * T) + px) - std::sin(px));
    y += 0.5 * options_.sway_amplitude_px *
         (std::sin(two_pi * t / (kSwayPeriodY * T) + py) - std::sin(py));
  }
  return {x, y};
}

}  // namespace kapfix
