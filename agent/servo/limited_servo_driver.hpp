#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "agent/servo/servo_driver.hpp"
#include "common/control/servo_limits.hpp"

namespace kapfix::agent {

// Monotonic time [µs]; injectable so that tests control the rate limit's clock.
using MonotonicClockUs = std::function<std::int64_t()>;
// std::chrono::steady_clock [µs].
std::int64_t SteadyClockNowUs();

// The one place where servo limits are enforced, in front of every backend (SPEC §2.8,
// issue 5: whatever it is sent, the agent never commands a servo outside its limits).
//
// SetAngle refuses NaN and ±∞ with an error and moves nothing (a broken controller must not
// move the camera, and the caller should know). Any finite request is passed through
// ServoLimiter: clamped into [min, max] and moved at most max_rate · dt from the angle last
// commanded, dt being the time since that command on this axis. Sparse commands therefore may
// jump as far as the elapsed time allows; the control loop commands every frame, so its steps
// stay small. A command the backend fails to carry out leaves the state unchanged.
//
// Open opens the backend and sends each axis to park_deg unlimited: where the servos stand
// before the first command is unknown, so there is nothing to limit the rate against.
// Park moves both axes towards park_deg through the same limits; AtPark() says when they are
// there (after a stall longer than (max − min) / rate, one Park gets there).
//
// Every refusal is logged (spdlog warn); clamped commands are counted and logged at debug.
class LimitedServoDriver : public ServoDriver {
 public:
  // Throws std::invalid_argument for a null backend or limits that are not IsValid.
  LimitedServoDriver(std::unique_ptr<ServoDriver> backend, ServoLimits pan, ServoLimits tilt,
                     MonotonicClockUs clock = SteadyClockNowUs);

  bool Open(std::string* error) override;
  // After the backend failed: opens it again and sends each axis the angle last accepted,
  // unlimited. Where the servos stand after a failure is unknown (a Maestro may have gone to
  // its hold position); the last angle is where the control loop believes them to be, so
  // fixation resumes without a jump in its model.
  bool Reopen(std::string* error);
  bool SetAngle(ServoAxis axis, double deg, std::string* error) override;
  bool Park(std::string* error) override;
  std::string Describe() const override;

  bool AtPark() const;
  double angle(ServoAxis axis) const;  // [deg] last angle the backend accepted
  const ServoLimits& limits(ServoAxis axis) const;
  std::uint64_t refused_count() const { return refused_; }  // non-finite requests
  std::uint64_t limited_count() const { return limited_; }  // requests changed by the limits

 private:
  struct AxisState {
    ServoLimiter limiter;
    double angle_deg;
    std::int64_t commanded_at_us = 0;
  };

  AxisState& State(ServoAxis axis) { return axis == ServoAxis::kPan ? pan_ : tilt_; }
  const AxisState& State(ServoAxis axis) const { return axis == ServoAxis::kPan ? pan_ : tilt_; }
  bool Command(ServoAxis axis, double target_deg, std::string* error);

  std::unique_ptr<ServoDriver> backend_;
  MonotonicClockUs clock_;
  AxisState pan_;
  AxisState tilt_;
  bool open_ = false;
  std::uint64_t refused_ = 0;
  std::uint64_t limited_ = 0;
};

}  // namespace kapfix::agent
