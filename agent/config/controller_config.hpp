#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace kapfix::agent {

enum class ControllerKind {
  kP,           // the thesis's proportional control through the calibration
  kPid,         // P plus integral and derivative terms
  kPredictive,  // feeds the swing's estimated phase and period forward (SPEC §3)
};

std::optional<ControllerKind> ParseControllerKind(std::string_view text);  // p|pid|predictive
std::string_view ToString(ControllerKind kind);

// The "controller" section (SPEC §2.8). The displacement is turned into degrees through the
// lens profile first, so the gains are dimensionless and per frame. Defaults:
// resources/README.md.
struct ControllerConfig {
  ControllerKind kind = ControllerKind::kPredictive;
  double kp = 0.8;                 // [1] share of the error corrected per frame
  double ki = 0.0;                 // [1/s] pid, predictive
  double kd = 0.0;                 // [s] pid, predictive
  double dead_band_px = 0.5;       // [px] displacements below this are not corrected
  double max_rate_deg_per_s = 90;  // [deg/s] controller output slew (servo limits still cap)

  // Every value within its field's range in the settings schema (kapfix.v1.Gains).
  bool IsValid(std::string* error) const;
};

}  // namespace kapfix::agent
