#pragma once

#include <optional>

#include "common/control/controller.hpp"

namespace kapfix {

// The operator's rate limit (ControllerGains::LimitRate) on the commands one
// controller issues: each target moves at most rate · dt from the previous target it let
// through — how fast the commanded angle may change, the servo's speed or less. Not from the
// `current` angles a frame was seen through: with an actuation delay of n frames those are n
// commands old, and limiting against them let the commands advance by rate · dt only once
// every n frames (agent --sim, kite, a 2-frame delay: half the configured rate, and 21 px
// RMS with the calibration ×0.6 where the benchmark, without that limit, held 4).
class CommandRateLimiter {
 public:
  // `target` limited to the gains' rate · dt from the previous target let through, or from
  // `current` before the first (and after Reset). Rate 0: no limit; dt ≤ 0 or non-finite
  // with a rate set: no time passed, the previous target stands.
  ServoTargets Limit(const ControllerGains& gains, const ServoTargets& target,
                     const ServoTargets& current, double dt_s);
  // A frame without a measurement: the targets hold at `current`, or head for
  // input.return_to (a lost lock) at the rate limit.
  ServoTargets Unmeasured(const ControllerGains& gains, const ControlInput& input,
                          const ServoTargets& current);
  // A target the controller issued without limiting (a hold at `current`): the next limit
  // starts from it.
  void Issued(const ServoTargets& target) { previous_ = target; }
  void Reset() { previous_.reset(); }

 private:
  std::optional<ServoTargets> previous_;
};

}  // namespace kapfix
