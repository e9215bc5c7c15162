#include "common/sim/kite_motion.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <mutex>
#include <numbers>
#include <stdexcept>

#include "common/sim/sim_random.hpp"

namespace kapfix {
namespace {

// Independent random streams of one seed.
constexpr std::uint64_t kJitterStream = 0x6b6974654a;  // "kiteJ"
constexpr std::uint64_t kGustStream = 0x6b69746547;    // "kiteG"
constexpr std::uint64_t kGustSizeStream = 0x6b69746553;
constexpr std::uint64_t kPhaseStream = 0x6b69746550;       // drift, sway, turbulence phases
constexpr std::uint64_t kStepGustStream = 0x6b69746554;    // broadband step gusts
constexpr std::uint64_t kTurbulenceStream = 0x6b69746557;  // broadband turbulence's noise

constexpr double kDriftPeriodFrames = 600;       // [frames] how slowly the swing period wanders
constexpr double kSwayPeriodX = 7.3;             // [swing periods] the slow sway along x
constexpr double kSwayPeriodY = 11.1;            // [swing periods] and along y
constexpr double kTurbulenceCorner = 1.0 / 150;  // [cycles/frame] Dryden-like corner
constexpr double kStepRiseFrames = 8;            // [frames] a step gust's 1 − cos rise
constexpr double kStepDecayFrames = 150;         // [frames] how fast the line drifts back

// Gusts older than this many τ contribute less than e^−40 of their amplitude.
constexpr double kGustHorizonTaus = 40.0;

// The damped pendulum e'' + 2α·e' + (α² + ω_d²)·e = 0 over one frame, for e = x − w, the
// view's offset from the rest position w where the wind holds the line (held over the
// frame): e₁ = c11·e₀ + c12·v₀, v₁ = c21·e₀ + c22·v₀ (exact, not an Euler step).
struct PendulumStep {
  double c11, c12, c21, c22;
};

PendulumStep PendulumOverOneFrame(double alpha, double omega_d) {
  const double decay = std::exp(-alpha);
  const double c = std::cos(omega_d), s = std::sin(omega_d);
  const double omega0_sq = alpha * alpha + omega_d * omega_d;
  return {decay * (c + alpha / omega_d * s), decay * s / omega_d, -decay * omega0_sq * s / omega_d,
          decay * (c - alpha / omega_d * s)};
}

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
  if (options_.gusts && options_.gust_model == KiteMotionOptions::GustModel::kBroadband) {
    StartWind();
  }
}

struct KiteMotion::WindResponse {
  std::mutex mutex;
  double a = 0;              // [1] the turbulence's per-frame low-pass pole
  double scale = 0;          // [px] the wind's push per unit of turbulence
  double turbulence = 0;     // [1] unit-RMS turbulence at the last frame
  double v = 0;              // [px/frame] the response's velocity at the last frame
  std::vector<double> wind;  // [px] the wind's push on the rest position, per frame
  std::vector<double> x;     // [px] the view's response, per frame
};

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

double KiteMotion::StepGusts(int frame) const {
  // A smooth push of the line's rest position that then drifts back. Ten decay times: what
  // is left (< 5·10⁻⁵ of the step) is far below a pixel.
  const int horizon = static_cast<int>(std::ceil(10.0 * kStepDecayFrames));
  const double rate = options_.gust_rate_per_frame / 4.0;
  double w = 0;
  for (int g = std::max(1, frame - horizon); g <= frame; ++g) {
    const double u = SimUniform(options_.seed, kStepGustStream, g);
    if (u >= rate) continue;
    const double size = (u / rate < 0.5 ? -1.0 : 1.0) *
                        (0.5 + 0.5 * SimUniform(options_.seed, kStepGustStream + 1, g));
    const double age = static_cast<double>(frame - g);
    const double rise = age >= kStepRiseFrames
                            ? 1.0
                            : 0.5 * (1.0 - std::cos(std::numbers::pi * age / kStepRiseFrames));
    w += size * options_.gust_amplitude_px * rise * std::exp(-age / kStepDecayFrames);
  }
  return w;
}

double KiteMotion::Wind(int frame) const {
  if (!wind_ || frame < 0) return 0.0;
  std::lock_guard lock(wind_->mutex);
  Extend(frame);
  return wind_->wind[static_cast<std::size_t>(frame)];
}

double KiteMotion::Broadband(int frame) const {
  std::lock_guard lock(wind_->mutex);
  Extend(frame);
  return wind_->x[static_cast<std::size_t>(frame)];
}

void KiteMotion::Extend(int frame) const {
  WindResponse& r = *wind_;
  const double alpha = 1.0 / options_.decay_frames;
  while (static_cast<int>(r.x.size()) <= frame) {
    const auto k = static_cast<int>(r.x.size()) - 1;
    // The swing's own angular frequency over this frame (the period drift included).
    const double omega_d = Phase(k + 1.0) - Phase(k);
    const PendulumStep p = PendulumOverOneFrame(alpha, omega_d);
    const double w = r.wind.back();  // held over the frame
    const double e = r.x.back() - w;
    r.x.push_back(w + p.c11 * e + p.c12 * r.v);
    r.v = p.c21 * e + p.c22 * r.v;
    r.turbulence = r.a * r.turbulence + std::sqrt(1.0 - r.a * r.a) *
                                            SimGaussian(options_.seed, kTurbulenceStream, k + 1);
    r.wind.push_back(r.scale * r.turbulence + StepGusts(k + 1));
  }
}

void KiteMotion::StartWind() {
  wind_ = std::make_shared<WindResponse>();
  WindResponse& r = *wind_;
  r.a = std::exp(-2.0 * std::numbers::pi * kTurbulenceCorner);
  const PendulumStep p = PendulumOverOneFrame(1.0 / options_.decay_frames,
                                              2.0 * std::numbers::pi / options_.period_frames);
  // State [turbulence u (unit RMS), response x, velocity v] over one frame; its stationary
  // covariance gives the scale that makes the view's response ½·gust_amplitude RMS, and the
  // flight starts from a draw of it (the wind blew before the first frame).
  Eigen::Matrix3d a;
  a << r.a, 0, 0, 1 - p.c11, p.c11, p.c12, -p.c21, p.c21, p.c22;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  covariance(0, 0) = 1.0 - r.a * r.a;
  // Doubling: after n rounds the sum over 2ⁿ frames; the pendulum forgets in ~τ frames.
  for (int round = 0; round < 40; ++round) {
    covariance += a * covariance * a.transpose();
    a = a * a;
  }
  const double sigma_x = std::sqrt(covariance(1, 1));
  r.scale = sigma_x > 0 ? 0.5 * options_.gust_amplitude_px / sigma_x : 0.0;
  const Eigen::Matrix3d root = covariance.llt().matrixL();
  const Eigen::Vector3d start =
      root * Eigen::Vector3d(SimGaussian(options_.seed, kTurbulenceStream, -1),
                             SimGaussian(options_.seed, kTurbulenceStream, -2),
                             SimGaussian(options_.seed, kTurbulenceStream, -3));
  r.turbulence = start(0);
  r.x.push_back(r.scale * start(1));
  r.v = r.scale * start(2);
  r.wind.push_back(r.scale * r.turbulence + StepGusts(0));
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
