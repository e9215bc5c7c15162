#include "agent/servo/limited_servo_driver.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace kapfix::agent {
namespace {

std::string Range(const ServoLimits& l) {
  return fmt::format("[{:g}, {:g}] deg ≤ {:g} deg/s", l.min_deg, l.max_deg, l.max_rate_deg_per_s);
}

}  // namespace

LimitedServoDriver::LimitedServoDriver(std::unique_ptr<ServoDriver> backend, ServoLimits pan,
                                       ServoLimits tilt, MonotonicClockUs clock,
                                       double frame_period_s)
    : backend_(std::move(backend)),
      clock_(std::move(clock)),
      frame_period_s_(frame_period_s),
      pan_{ServoLimiter(pan), pan.park_deg},
      tilt_{ServoLimiter(tilt), tilt.park_deg} {
  if (!backend_) throw std::invalid_argument("LimitedServoDriver: no backend");
  if (!clock_) throw std::invalid_argument("LimitedServoDriver: no clock");
  if (!std::isfinite(frame_period_s_) || frame_period_s_ <= 0) {
    throw std::invalid_argument("LimitedServoDriver: frame period must be > 0 s");
  }
}

bool LimitedServoDriver::Open(std::string* error) {
  open_ = false;
  if (!backend_->Open(error)) return false;
  for (const ServoAxis axis : {ServoAxis::kPan, ServoAxis::kTilt}) {
    AxisState& s = State(axis);
    s.angle_deg = s.limiter.limits().park_deg;
    s.placed = false;
    double read = 0;
    std::string why;
    // A device that tells where the servo stands: slew from there, no unlimited first move.
    if (backend_->ReadAngle(axis, &read, &why) && std::isfinite(read)) {
      s.angle_deg = read;
      s.placed = true;
    }
    s.commanded_at_us = clock_();
  }
  open_ = true;
  return true;
}

bool LimitedServoDriver::Reopen(std::string* error) {
  Suspend();
  const BackendReopen reopened = OpenBackend();
  if (!reopened.ok) {
    if (error) *error = reopened.error;
    return false;
  }
  AdoptBackend(reopened);
  return true;
}

LimitedServoDriver::BackendReopen LimitedServoDriver::OpenBackend() {
  BackendReopen reopened;
  reopened.ok = backend_->Open(&reopened.error);
  if (!reopened.ok) return reopened;
  for (const ServoAxis axis : {ServoAxis::kPan, ServoAxis::kTilt}) {
    double read = 0;
    std::string why;
    if (backend_->ReadAngle(axis, &read, &why) && std::isfinite(read)) {
      (axis == ServoAxis::kPan ? reopened.pan_deg : reopened.tilt_deg) = read;
    }
  }
  return reopened;
}

void LimitedServoDriver::AdoptBackend(const BackendReopen& reopened) {
  for (const ServoAxis axis : {ServoAxis::kPan, ServoAxis::kTilt}) {
    AxisState& s = State(axis);
    const std::optional<double>& read =
        axis == ServoAxis::kPan ? reopened.pan_deg : reopened.tilt_deg;
    if (read) {
      if (*read != s.angle_deg) {
        spdlog::info(
            "servo {}: at {:g} deg after the outage (last commanded {:g} deg); slewing "
            "from there at the rate limit",
            ToString(axis), *read, s.angle_deg);
      }
      s.angle_deg = *read;  // outside the limits: ServoLimiter takes the nearest limit
      s.placed = true;
    }
    s.commanded_at_us = clock_();
  }
  open_ = true;
}

bool LimitedServoDriver::Command(ServoAxis axis, double target_deg, double dt_s,
                                 std::string* error) {
  if (!open_) {
    if (error) *error = Describe() + ": not open";
    return false;
  }
  AxisState& s = State(axis);
  const std::int64_t now = clock_();
  if (!s.placed) {
    // Where the servo stands is unknown: the first command after Open goes to park.
    const double park = s.limiter.limits().park_deg;
    if (!backend_->SetAngle(axis, park, error)) return false;
    spdlog::info("servo {}: first command since open: to park {:g} deg", ToString(axis), park);
    s.angle_deg = park;
    s.commanded_at_us = now;
    s.placed = true;
    return true;
  }
  if (std::isnan(dt_s)) dt_s = static_cast<double>(now - s.commanded_at_us) * 1e-6;
  // The hard step bound: however long since the last command, one step covers at most one
  // frame period at the rate limit.
  dt_s = std::min(dt_s, frame_period_s_);
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
  return Command(axis, deg, std::numeric_limits<double>::quiet_NaN(), error);
}

bool LimitedServoDriver::Park(std::string* error) {
  return StepTowardsPark(std::numeric_limits<double>::quiet_NaN(), error);
}

bool LimitedServoDriver::StepTowardsPark(double dt_s, std::string* error) {
  // Both axes are tried even if the first fails: parking one is better than none.
  std::string pan_error;
  std::string tilt_error;
  const bool pan_ok = Command(ServoAxis::kPan, pan_.limiter.limits().park_deg, dt_s, &pan_error);
  const bool tilt_ok =
      Command(ServoAxis::kTilt, tilt_.limiter.limits().park_deg, dt_s, &tilt_error);
  if (pan_ok && tilt_ok) return true;
  if (error) *error = !pan_ok ? pan_error : tilt_error;
  if (!pan_ok && !tilt_ok && error && pan_error != tilt_error) *error += "; " + tilt_error;
  spdlog::warn("servo park failed: {}", pan_ok ? tilt_error : pan_error);
  return false;
}

bool LimitedServoDriver::ParkAndWait(const std::function<void()>& wait_one_period,
                                     std::string* error) {
  // One step per frame period; the farthest an axis can be from park is its whole range, so
  // this many steps always get there (+1 for a first command that goes to park unlimited).
  double steps = 1;
  for (const ServoAxis axis : {ServoAxis::kPan, ServoAxis::kTilt}) {
    const ServoLimits& l = limits(axis);
    steps = std::max(steps, std::ceil((l.max_deg - l.min_deg) / max_step_deg(axis)) + 1);
  }
  for (int step = 0; step < static_cast<int>(steps) + 1; ++step) {
    if (!StepTowardsPark(frame_period_s_, error)) return false;
    if (AtPark()) return true;
    if (wait_one_period) wait_one_period();
  }
  if (error) *error = Describe() + ": not at park after " + std::to_string(steps) + " steps";
  return false;  // not reached: every step moves each axis max_step_deg closer
}

double LimitedServoDriver::max_step_deg(ServoAxis axis) const {
  return limits(axis).max_rate_deg_per_s * frame_period_s_;
}

bool LimitedServoDriver::AtPark() const {
  return pan_.placed && tilt_.placed && pan_.angle_deg == pan_.limiter.limits().park_deg &&
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
