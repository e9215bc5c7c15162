#include "common/control/servo_limits.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace kapfix {
namespace {

// Hobby servos turn ±90 deg at most; ±180 leaves room for continuous-range mounts while
// still catching unit mistakes (radians for degrees gives tiny values, µs gives huge ones).
constexpr double kMaxAbsDeg = 180;

}  // namespace

bool ServoLimits::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (!std::isfinite(min_deg) || !std::isfinite(max_deg) || !(min_deg < max_deg)) {
    return fail("servo limits must be finite with min_deg < max_deg, got [" +
                std::to_string(min_deg) + ", " + std::to_string(max_deg) + "] deg");
  }
  if (min_deg < -kMaxAbsDeg || max_deg > kMaxAbsDeg) {
    return fail("servo limits must lie within ±180 deg, got [" + std::to_string(min_deg) + ", " +
                std::to_string(max_deg) + "] deg");
  }
  if (!std::isfinite(max_rate_deg_per_s) || max_rate_deg_per_s <= 0) {
    return fail("servo max_rate_deg_per_s must be > 0, got " + std::to_string(max_rate_deg_per_s));
  }
  if (!(park_deg >= min_deg && park_deg <= max_deg)) {
    return fail("servo park_deg " + std::to_string(park_deg) + " is outside [" +
                std::to_string(min_deg) + ", " + std::to_string(max_deg) + "] deg");
  }
  return true;
}

ServoLimiter::ServoLimiter(ServoLimits limits) : limits_(limits) {
  std::string error;
  if (!limits_.IsValid(&error)) throw std::invalid_argument("ServoLimiter: " + error);
}

double ServoLimiter::Limit(double target_deg, double current_deg, double dt_s) const {
  const double current = std::isnan(current_deg)
                             ? limits_.park_deg
                             : std::clamp(current_deg, limits_.min_deg, limits_.max_deg);
  if (std::isnan(target_deg)) return current;
  const double target = std::clamp(target_deg, limits_.min_deg, limits_.max_deg);
  if (!(dt_s > 0)) return current;  // also NaN
  // Both angles are finite and inside ±180, so the difference cannot overflow; the step may
  // be +∞ (huge or infinite dt). Returning the target itself when it is in reach (rather than
  // current + difference) keeps rounding from stepping an ulp past a limit.
  const double step = limits_.max_rate_deg_per_s * dt_s;
  if (std::abs(target - current) <= step) return target;
  return std::clamp(target > current ? current + step : current - step, limits_.min_deg,
                    limits_.max_deg);
}

}  // namespace kapfix
