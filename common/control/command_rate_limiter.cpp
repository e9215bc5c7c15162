#include "common/control/command_rate_limiter.hpp"

namespace kapfix {

ServoTargets CommandRateLimiter::Limit(const ControllerGains& gains, const ServoTargets& target,
                                       const ServoTargets& current, double dt_s) {
  const ServoTargets limited = gains.LimitRate(target, previous_.value_or(current), dt_s);
  previous_ = limited;
  return limited;
}

ServoTargets CommandRateLimiter::Unmeasured(const ControllerGains& gains, const ControlInput& input,
                                            const ServoTargets& current) {
  if (input.return_to) return Limit(gains, *input.return_to, current, input.dt_s);
  Issued(current);
  return current;
}

}  // namespace kapfix
