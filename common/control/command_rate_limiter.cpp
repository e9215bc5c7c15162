#include "common/control/command_rate_limiter.hpp"

namespace kapfix {

ServoTargets CommandRateLimiter::Limit(const ControllerGains& gains, const ServoTargets& target,
                                       const ServoTargets& current, double dt_s) {
  const ServoTargets limited = gains.LimitRate(target, previous_.value_or(current), dt_s);
  previous_ = limited;
  return limited;
}

}  // namespace kapfix
