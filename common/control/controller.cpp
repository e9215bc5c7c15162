#include "common/control/controller.hpp"

#include <algorithm>
#include <cmath>

namespace kapfix {

bool ControllerGains::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  for (const double g : {p, i, d}) {
    if (!std::isfinite(g) || g < 0) return fail("gains must be finite and ≥ 0");
  }
  if (!std::isfinite(dead_band_px) || dead_band_px < 0) {
    return fail("dead band must be ≥ 0 px, got " + std::to_string(dead_band_px));
  }
  if (!std::isfinite(rate_limit_deg_per_s) || rate_limit_deg_per_s < 0) {
    return fail("rate limit must be ≥ 0 deg/s (0 = none), got " +
                std::to_string(rate_limit_deg_per_s));
  }
  if (!std::isfinite(integral_limit_px) || integral_limit_px < 0) {
    return fail("integral limit must be ≥ 0 px, got " + std::to_string(integral_limit_px));
  }
  return true;
}

double ControllerGains::Correctable(double displacement_px) const {
  return std::abs(displacement_px) >= dead_band_px ? displacement_px : 0.0;
}

double ControllerGains::BeyondDeadBand(double displacement_px) const {
  return std::max(0.0, std::abs(displacement_px) - dead_band_px);
}

ServoTargets ControllerGains::LimitRate(const ServoTargets& target, const ServoTargets& from,
                                        double dt_s) const {
  return ApplyRateLimit(target, from, rate_limit_deg_per_s, dt_s);
}

ControllerGains ControllerGains::WithoutRateLimit() const {
  ControllerGains gains = *this;
  gains.rate_limit_deg_per_s = 0;
  return gains;
}

ServoTargets ApplyRateLimit(const ServoTargets& target, const ServoTargets& current,
                            double rate_deg_per_s, double dt_s) {
  if (rate_deg_per_s <= 0.0) return target;
  const double step = std::isfinite(dt_s) && dt_s > 0.0 ? rate_deg_per_s * dt_s : 0.0;
  return {current.pan_deg + std::clamp(target.pan_deg - current.pan_deg, -step, step),
          current.tilt_deg + std::clamp(target.tilt_deg - current.tilt_deg, -step, step)};
}

}  // namespace kapfix
