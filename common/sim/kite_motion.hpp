#pragma once

#include <cstdint>
#include <memory>
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
  // decay (an AR(2) fits them exactly). kBroadband: wind as a force on the pendulum (the rig
  // under the line): turbulence whose spectrum is not the swing's — a Dryden-like first-order
  // low-pass of white noise (corner 1/150 cycles per frame) — plus occasional step gusts
  // (rate gust_rate_per_frame / 4) that push the line's rest position over by up to
  // ±gust_amplitude and let it drift back over ~150 frames. The wind moves the pendulum's
  // rest position; the view follows with the pendulum's own dynamics (period, decay τ), so
  // the rig's inertia low-passes it (∝ 1/f² above the swing's frequency) and the swing's
  // resonance shows in it, as a real rig's does. The turbulence is scaled so that the view's
  // stationary response has RMS ½·gust_amplitude.
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
// Frames before 0 are the rest position (0, 0). The period drift and the sway are
// closed-form functions of t; the broadband wind's response is integrated in frame order
// from a stationary start (the wind blew before the flight) and kept, so random access stays
// exact.
class KiteMotion final : public PlatformMotion {
 public:
  // Throws std::invalid_argument for options that are not IsValid.
  explicit KiteMotion(KiteMotionOptions options);

  cv::Point2d LineOfSight(int frame) const override;
  // The gusts starting in [first_frame, last_frame] (none when gusts are off).
  std::vector<KiteGust> Gusts(int first_frame, int last_frame) const;
  // [px] kBroadband: the wind's push on the line's rest position at `frame` (turbulence and
  // step gusts), the force the pendulum low-passes; 0 for the other models.
  double Wind(int frame) const;
  const KiteMotionOptions& options() const { return options_; }

 private:
  // The gust starting at `frame`, if one does; amplitude 0 otherwise.
  double GustAmplitude(int frame) const;
  // [rad] the swing's phase at t: ω·t with the period drift integrated in.
  double Phase(double t) const;
  // [px] the step gusts' push on the rest position at `frame` (GustModel::kBroadband).
  double StepGusts(int frame) const;
  // [px] the pendulum's response to the wind at `frame` (GustModel::kBroadband).
  double Broadband(int frame) const;
  // Sets the wind's scale and its stationary first frame (GustModel::kBroadband).
  void StartWind();
  // Integrates the wind's response up to `frame`; wind_->mutex held.
  void Extend(int frame) const;

  KiteMotionOptions options_;
  // The wind's response is integrated frame by frame (the pendulum's state carries over), so
  // it is kept as it is computed: random access stays exact and cheap. Shared by copies
  // (same options, same numbers) and guarded for callers on several threads.
  struct WindResponse;
  std::shared_ptr<WindResponse> wind_;
};

}  // namespace kapfix
