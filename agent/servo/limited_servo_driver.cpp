#include "agent/servo/limited_servo_driver.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace kapfix::agent {
namespace {

std::string Range(const ServoLimits& l) {
  return fmt::format("[{:g}, {:g}] deg ≤ {:g} deg/s", l.min_deg, l.max_deg, l.max_rate_deg_per_s);
}

}  // namespace

std::int64_t SteadyClockNowUs() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

LimitedServoDriver::LimitedServoDriver(std::unique_ptr<ServoDriver> backend, ServoLimits pan,
                                       ServoLimits tilt, MonotonicClockUs clock)
    : backend_(std::move(backend)),
      clock_(std::move(clock)),
      pan_{ServoLimiter(pan), pan.park_deg},
      tilt_{ServoLimiter(tilt), tilt.park_deg} {
  if (!backend_) throw std::invalid_argument("LimitedServoDriver: no backend");
  if (!clock_) throw std::invalid_argument("LimitedServoDriver: no clock");
}

bool LimitedServoDriver::Open(std::string* error) {
  open_ = false;
  if (!backend_->Open(error)) return false;
  for (const ServoAxis axis : {ServoAxis::kPan, ServoAxis::kTilt}) {
    AxisState& s = State(axis);
    const double park = s.limiter.limits().park_deg;
    if (!backend_->SetAngle(axis, park, error)) return false;
    s.angle_deg = park;
    s.commanded_at_us = clock_();
  }
  open_ = true;
  return true;
}

bool LimitedServoDriver::Reopen(std::string* error) {
  open_ = false;
  if (!backend_->Open(error)) return false;
  for (const ServoAxis axis : {ServoAxis::kPan, ServoAxis::kTilt}) {
    AxisState& s = State(axis);
    if (!backend_->SetAngle(axis, s.angle_deg, error)) return false;
    s.commanded_at_us = clock_();
  }
  open_ = true;
  return true;
}

bool LimitedServoDriver::Command(ServoAxis axis, double target_deg, std::string* error) {
  if (!open_) {
    if (error) *error = Describe() + ": not open";
    return false;
  }
  AxisState& s = State(axis);
  const std::int64_t now = clock_();
  const double dt_s = static_cast<double>(now - s.commanded_at_us) * 1e-6;
  const double limited = s.limiter.Limit(target_deg, s.angle_deg, dt_s);
  if (limited != target_deg) {
    ++limited_;
    spdlog::debug("servo {}: {:g} deg limited to {:g} deg", ToString(axis), target_deg, limited);
  }
  if (!backend_->SetAngle(axis, limited, error)) return false;
  s.angle_deg = limited;
  s.commanded_at_us = now;
  return true;
}

bool LimitedServoDriver::SetAngle(ServoAxis axis, double deg, std::string* error) {
  if (!std::isfinite(deg)) {
    ++refused_;
    const std::string reason =
        fmt::format("servo {}: refused a non-finite angle ({}); not moved", ToString(axis), deg);
    spdlog::warn("{}", reason);
    if (error) *error = reason;
    return false;
  }
  return Command(axis, deg, error);
}

bool LimitedServoDriver::Park(std::string* error) {
  // Both axes are tried even if the first fails: parking one is better than none.
  std::string pan_error;
  std::string tilt_error;
  const bool pan_ok = Command(ServoAxis::kPan, pan_.limiter.limits().park_deg, &pan_error);
  const bool tilt_ok = Command(ServoAxis::kTilt, tilt_.limiter.limits().park_deg, &tilt_error);
  if (pan_ok && tilt_ok) return true;
  if (error) *error = !pan_ok ? pan_error : tilt_error;
  if (!pan_ok && !tilt_ok && error && pan_error != tilt_error) *error += "; " + tilt_error;
  spdlog::warn("servo park failed: {}", pan_ok ? tilt_error : pan_error);
  return false;
}

bool LimitedServoDriver::AtPark() const {
  return pan_.angle_deg == pan_.limiter.limits().park_deg &&
         tilt_.angle_deg == tilt_.limiter.limits().park_deg;
}

double LimitedServoDriver::angle(ServoAxis axis) const { return State(axis).angle_deg; }

const ServoLimits& LimitedServoDriver::limits(ServoAxis axis) const {
  return State(axis).limiter.limits();
}

std::string LimitedServoDriver::Describe() const {
  return backend_->Describe() + ", limits pan " + Range(pan_.limiter.limits()) + ", tilt " +
         Range(tilt_.limiter.limits());
}

}  // namespace kapfix::agent
