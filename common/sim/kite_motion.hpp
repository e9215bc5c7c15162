#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/sim/platform_motion.hpp"

namespace kapfix {

struct KiteMotionOptions {
  double amplitude_px = 100;               // A [px] initial swing amplitude along X
  double period_frames = 40;               // T [frames] pendulum period
  double decay_frames = 400;               // τ [frames] amplitude decays as e^(−t/τ)
  double jitter_sigma_px = 2;              // σ [px] independent Y jitter per frame
  bool gusts = false;                      // random impulses that restart a swing
  double gust_rate_per_frame = 1.0 / 100;  // probability of a gust starting at a frame
  double gust_amplitude_px = 30;           // [px] largest gust amplitude
  std::uint32_t seed = 1;

  bool IsValid(std::string* error) const;
};

// One gust: from `frame` on it adds amplitude_px·sin(2π(t−g)/T)·e^(−(t−g)/τ) to x.
struct KiteGust {
  int frame = 0;
  double amplitude_px = 0;  // [px] signed
};

// Damped pendulum under a kite line (SPEC §3):
//   x(t) = A·sin(2πt/T)·e^(−t/τ) + Σ gusts,   y(t) = σ·N(0, 1) per frame.
// A gust starts at frame g ≥ 1 with probability gust_rate_per_frame, decided per frame from
// (seed, g); its amplitude is uniform in [½, 1]·gust_amplitude_px with a random sign. A gust
// starts at zero and swings (an impulse to the velocity, not a jump in position). Gusts
// older than 40τ (contribution < e^−40) are not summed, which bounds the cost per call.
// Frames before 0 are the rest position (0, 0).
class KiteMotion final : public PlatformMotion {
 public:
  // Throws std::invalid_argument for options that are not IsValid.
  explicit KiteMotion(KiteMotionOptions options);

  cv::Point2d LineOfSight(int frame) const override;
  // The gusts starting in [first_frame, last_frame] (none when gusts are off).
  std::vector<KiteGust> Gusts(int first_frame, int last_frame) const;
  const KiteMotionOptions& options() const { return options_; }

 private:
  // The gust starting at `frame`, if one does; amplitude 0 otherwise.
  double GustAmplitude(int frame) const;

  KiteMotionOptions options_;
};

}  // namespace kapfix
