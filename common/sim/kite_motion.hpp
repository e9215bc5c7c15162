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
  // What `gusts` raises. kPeriodic: impulses that swing with the pendulum's own period and
  // decay (an AR(2) fits them exactly). kBroadband: wind turbulence whose spectrum is not the
  // swing's — a Dryden-like low-pass (corner 1/150 cycles per frame) of RMS ½·gust_amplitude
  // — plus occasional step gusts (rate gust_rate_per_frame / 4) that push the line over by up
  // to ±gust_amplitude and let it drift back over ~150 frames.
  enum class GustModel { kPeriodic, kBroadband };
  GustModel gust_model = GustModel::kPeriodic;
  // [1] the swing period wanders by up to ± this share over the flight (line length and
  // wind change): T(t) = T / (1 + F·sin(2πt/600 + φ)), 0 ≤ F ≤ 0.5.
  double period_drift = 0;
  // [px] amplitude of a second, slower sway of the line (period 7.3 T along x, 11.1 T at
  // half the amplitude along y) on top of the pendulum; 0 = none.
  double sway_amplitude_px = 0;
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
// Frames before 0 are the rest position (0, 0). The period drift and the sway (and the
// broadband gusts) are closed-form functions of t, so random access stays exact.
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
  // [rad] the swing's phase at t: ω·t with the period drift integrated in.
  double Phase(double t) const;
  // [px] broadband turbulence and step gusts at `frame` (GustModel::kBroadband).
  double Broadband(int frame) const;

  KiteMotionOptions options_;
};

}  // namespace kapfix
