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
  if (!options_.gusts) return gusts;
  for (int g = std::max(first_frame, 1); g <= last_frame; ++g) {
    const double a = GustAmplitude(g);
    if (a != 0.0) gusts.push_back({g, a});
  }
  return gusts;
}

cv::Point2d KiteMotion::LineOfSight(int frame) const {
  if (frame < 0) return {0.0, 0.0};
  const double t = frame;
  const double omega = 2.0 * std::numbers::pi / options_.period_frames;
  const double tau = options_.decay_frames;
  double x = options_.amplitude_px * std::sin(omega * t) * std::exp(-t / tau);
  if (options_.gusts) {
    const double horizon = std::min(t, std::ceil(kGustHorizonTaus * tau));
    for (int g = frame - static_cast<int>(horizon); g <= frame; ++g) {
      const double a = GustAmplitude(g);
      if (a == 0.0) continue;
      const double age = t - g;
      x += a * std::sin(omega * age) * std::exp(-age / tau);
    }
  }
  const double y = options_.jitter_sigma_px * SimGaussian(options_.seed, kJitterStream, frame);
  return {x, y};
}

}  // namespace kapfix
