#include "common/sim/boat_motion.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "common/sim/sim_random.hpp"

namespace kapfix {
namespace {

constexpr std::uint64_t kJitterStream = 0x626f61744a;  // "boatJ"
constexpr std::uint64_t kWaveStream = 0x626f617457;    // "boatW"

constexpr double kMinWavePeriod = 7.0;   // [frames]
constexpr double kMaxWavePeriod = 30.0;  // [frames]
constexpr int kMaxWaves = 64;

bool Finite(double v) { return std::isfinite(v); }

}  // namespace

bool BoatMotionOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (!Finite(roll_amplitude_px) || roll_amplitude_px < 0) {
    return fail("boat roll amplitude must be ≥ 0 px, got " + std::to_string(roll_amplitude_px));
  }
  if (!Finite(roll_period_frames) || roll_period_frames <= 0) {
    return fail("boat roll period must be > 0 frames, got " + std::to_string(roll_period_frames));
  }
  if (!Finite(wave_amplitude_px) || wave_amplitude_px < 0) {
    return fail("boat wave amplitude must be ≥ 0 px, got " + std::to_string(wave_amplitude_px));
  }
  if (waves < 0 || waves > kMaxWaves) {
    return fail("boat waves must be 0…" + std::to_string(kMaxWaves) + ", got " +
                std::to_string(waves));
  }
  if (!Finite(jitter_sigma_px) || jitter_sigma_px < 0) {
    return fail("boat jitter σ must be ≥ 0 px, got " + std::to_string(jitter_sigma_px));
  }
  return true;
}

BoatMotion::BoatMotion(BoatMotionOptions options) : options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument("BoatMotion: " + error);
  for (int k = 0; k < options_.waves; ++k) {
    // Three draws per wave, from consecutive indices of the wave stream.
    const double ua = SimUniform(options_.seed, kWaveStream, 3 * static_cast<std::int64_t>(k));
    const double up = SimUniform(options_.seed, kWaveStream, 3 * k + 1);
    const double uf = SimUniform(options_.seed, kWaveStream, 3 * k + 2);
    waves_.push_back({ua * options_.wave_amplitude_px,
                      kMinWavePeriod + up * (kMaxWavePeriod - kMinWavePeriod),
                      uf * 2.0 * std::numbers::pi});
  }
}

cv::Point2d BoatMotion::LineOfSight(int frame) const {
  if (frame < 0) return {0.0, 0.0};
  const double t = frame;
  double y = options_.roll_amplitude_px *
             std::sin(2.0 * std::numbers::pi * t / options_.roll_period_frames);
  for (const BoatWave& w : waves_) {
    y += w.amplitude_px * std::sin(2.0 * std::numbers::pi * t / w.period_frames + w.phase_rad);
  }
  const double x = options_.jitter_sigma_px * SimGaussian(options_.seed, kJitterStream, frame);
  return {x, y};
}

}  // namespace kapfix
