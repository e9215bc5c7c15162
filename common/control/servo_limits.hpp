#pragma once

#include <string>

namespace kapfix {

// Hard limits of one servo axis (SPEC §2.8: the agent may never command a servo outside its
// configured limits, whatever it is sent). Angles are relative to the axis's centre.
struct ServoLimits {
  double min_deg = -45;             // [deg] lowest angle ever commanded
  double max_deg = 45;              // [deg] highest angle ever commanded
  double max_rate_deg_per_s = 120;  // [deg/s] fastest commanded motion
  double park_deg = 0;              // [deg] hold position, inside [min_deg, max_deg]

  // Finite values, min < max, |angles| ≤ 180 deg, rate > 0 and park inside the range.
  bool IsValid(std::string* error) const;
};

// Turns any requested angle into one that is safe to send: inside [min, max] and no further
// from the current angle than the rate allows in dt. Pure and stateless, so that every
// servo backend shares exactly this one rule.
class ServoLimiter {
 public:
  // Throws std::invalid_argument for limits that are not IsValid.
  explicit ServoLimiter(ServoLimits limits);

  // The angle to command [deg], given the request, the angle last commanded and the time
  // since then [s].
  //  - NaN target: current (no motion). ±∞ and huge targets are clamped like any other.
  //  - A current angle outside [min, max] is taken as the nearest limit (the result is then
  //    inside the limits even if that jump exceeds the rate); a NaN current as park_deg.
  //  - dt ≤ 0 or NaN allows no motion; dt = +∞ allows any motion inside the limits.
  double Limit(double target_deg, double current_deg, double dt_s) const;

  const ServoLimits& limits() const { return limits_; }

 private:
  ServoLimits limits_;
};

}  // namespace kapfix
