#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/sim/platform_motion.hpp"

namespace kapfix {

struct BoatMotionOptions {
  double roll_amplitude_px = 60;    // A [px] roll amplitude along Y
  double roll_period_frames = 120;  // T [frames] the slow roll
  double wave_amplitude_px = 8;     // [px] largest amplitude of one superposed wave
  int waves = 3;                    // number of superposed waves, 0…64
  double jitter_sigma_px = 1;       // σ [px] independent X jitter per frame
  std::uint32_t seed = 1;

  bool IsValid(std::string* error) const;
};

// One superposed wave: amplitude_px·sin(2πt/period_frames + phase_rad).
struct BoatWave {
  double amplitude_px = 0;   // [px] in [0, wave_amplitude_px]
  double period_frames = 0;  // [frames] in [7, 30]
  double phase_rad = 0;      // [rad] in [0, 2π)
};

// A boat rolling (SPEC §3): the line of sight moves along Y,
//   y(t) = A·sin(2πt/T) + Σ_k a_k·sin(2πt/T_k + φ_k),   x(t) = σ·N(0, 1) per frame,
// with the waves' a_k, T_k, φ_k drawn uniformly from the seed once, at construction.
// Frames before 0 are the rest position (0, 0).
class BoatMotion final : public PlatformMotion {
 public:
  // Throws std::invalid_argument for options that are not IsValid.
  explicit BoatMotion(BoatMotionOptions options);

  cv::Point2d LineOfSight(int frame) const override;
  const std::vector<BoatWave>& waves() const { return waves_; }
  const BoatMotionOptions& options() const { return options_; }

 private:
  BoatMotionOptions options_;
  std::vector<BoatWave> waves_;
};

}  // namespace kapfix
