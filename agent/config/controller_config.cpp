#include "agent/config/controller_config.hpp"

#include <cmath>

namespace kapfix::agent {

std::optional<ControllerKind> ParseControllerKind(std::string_view text) {
  if (text == "p") return ControllerKind::kP;
  if (text == "pid") return ControllerKind::kPid;
  if (text == "predictive") return ControllerKind::kPredictive;
  return std::nullopt;
}

std::string_view ToString(ControllerKind kind) {
  switch (kind) {
    case ControllerKind::kP:
      return "p";
    case ControllerKind::kPid:
      return "pid";
    case ControllerKind::kPredictive:
      return "predictive";
  }
  return "?";
}

bool ControllerConfig::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  auto in = [](double v, double lo, double hi) { return std::isfinite(v) && v >= lo && v <= hi; };
  if (!in(kp, 0, 10) || kp == 0)
    return fail("controller.kp: must be in (0, 10], got " + std::to_string(kp));
  if (!in(ki, 0, 10)) return fail("controller.ki: must be 0…10, got " + std::to_string(ki));
  if (!in(kd, 0, 10)) return fail("controller.kd: must be 0…10, got " + std::to_string(kd));
  if (!in(dead_band_px, 0, 50)) {
    return fail("controller.dead_band_px: must be 0…50 px, got " + std::to_string(dead_band_px));
  }
  if (!in(max_rate_deg_per_s, 0, 1000) || max_rate_deg_per_s == 0) {
    return fail("controller.max_rate_deg_per_s: must be in (0, 1000], got " +
                std::to_string(max_rate_deg_per_s));
  }
  return true;
}

}  // namespace kapfix::agent
