#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "common/sim/simulated_platform.hpp"

namespace kapfix {

// The field's disturbances the simulated world adds to SPEC §3's textbook swing (issue 9).
// Each is off in the nominal world; all are seeded by the platform's seeds, so a flight is
// deterministic. ApplyTo writes them into a SimulatedPlatformOptions; calibration_error is
// not the platform's but the controller's (EvaluateClosedLoop and the agent scale the lens
// calibration they hand it).
struct WorldOptions {
  enum class Gusts { kOff, kPeriodic, kBroadband };
  Gusts gusts = Gusts::kPeriodic;  // the nominal world's same-period gusts
  double period_drift = 0;         // [1] swing period wanders by ± this share, 0…0.5
  bool sway = false;               // a slower second sway of the line (±20 px in x)
  double roll_deg = 0;             // [deg] image roll up to ± this, 0…30, with keystone
  bool blur = false;               // motion blur over half a frame period of the view's motion
  bool exposure_steps = false;     // auto-exposure gain steps of up to ±20 %
  int latency_jitter = 0;          // [frames] servo latency varies in 1…N; 0 = fixed, else 1…10
  double frame_drops = 0;          // [1] share of frames the camera loses, 0…0.5
  double calibration_error = 1.0;  // [1] controller's deg/px ÷ the true one, 0.5…2

  bool IsValid(std::string* error) const;
  // The disturbances turned on (not the nominal world's), e.g. "gusts broadband, roll 3°";
  // "nominal" when none is.
  std::string Describe() const;
  // Writes the world into `platform` (kite motion, camera, servos, frame drops).
  void ApplyTo(SimulatedPlatformOptions* platform) const;

  static WorldOptions Nominal() { return {}; }
  // Every disturbance on at field-like levels: broadband gusts, period drift ±15 %, sway,
  // roll ±3°, motion blur, exposure steps, servo latency 1…2 frames, 2 % frames dropped,
  // calibration 1.3 × the true deg/px.
  static WorldOptions Realistic();
  // "nominal" or "realistic"; nothing for another name.
  static std::optional<WorldOptions> Preset(std::string_view name);
};

std::optional<WorldOptions::Gusts> ParseWorldGusts(
    std::string_view text);  // off|periodic|broadband
std::string_view ToString(WorldOptions::Gusts gusts);

}  // namespace kapfix
