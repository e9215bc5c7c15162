#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "agent/servo/servo_driver.hpp"
#include "common/control/servo_limits.hpp"
#include "common/time/steady_clock.hpp"

namespace kapfix::agent {

// Monotonic time [µs]; injectable so that tests control the rate limit's clock.
using MonotonicClockUs = std::function<std::int64_t()>;
using kapfix::SteadyClockNowUs;

// [s] the step bound's period when none is given: a 30 frames/s camera.
inline constexpr double kDefaultServoFramePeriodS = 1.0 / 30;

// The one place where servo limits are enforced, in front of every backend (SPEC §2.8,
// issues 5 and 10: whatever it is sent, the agent never commands a servo outside its limits
// nor one step larger than max_rate · frame_period).
//
// SetAngle refuses NaN and ±∞ with an error and moves nothing (a broken controller must not
// move the camera, and the caller should know). Any finite request is passed through
// ServoLimiter: clamped into [min, max] and moved at most max_rate · min(dt, frame_period)
// from the angle last commanded, dt being the time since that command on this axis. The cap
// on dt is the hard guarantee: after any gap (a camera outage, a stall, a reopen) one command
// moves a servo no further than one frame's worth at the rate limit, so the servos slew back
// rather than snap. A command the backend fails to carry out leaves the state unchanged.
//
// Open opens the backend and moves nothing. Where the device tells where a servo stands
// (ReadAngle), commands slew from there; otherwise the first command sends the axis to park_deg
// (the one unlimited command, as there is nothing to limit it against; a Maestro's own speed limit
// still applies). The agent sends that first command only once a camera frame and the servo driver
// are both healthy. Reopen (after the backend failed) moves nothing either; each axis's position is
// read back from the device where it can tell (a Maestro's serial timeout may have sent the servos
// home), else taken as the angle last accepted; commands then slew from there at the rate.
// Park moves both axes one limited step towards park_deg; ParkAndWait steps until both are
// there (AtPark), waiting one frame period between steps.
//
// Every refusal is logged (spdlog warn); clamped commands are counted and logged at debug.
class LimitedServoDriver : public ServoDriver {
 public:
  // Throws std::invalid_argument for a null backend or limits that are not IsValid.
  // Throws std::invalid_argument also for a frame period that is not > 0 and finite.
  LimitedServoDriver(std::unique_ptr<ServoDriver> backend, ServoLimits pan, ServoLimits tilt,
                     MonotonicClockUs clock = SteadyClockNowUs,
                     double frame_period_s = kDefaultServoFramePeriodS);

  bool Open(std::string* error) override;
  // After the backend failed: opens it again without moving anything; each axis's angle
  // becomes the one the device reports (ReadAngle), else stays the last accepted one.
  // Suspend(), then OpenBackend(), then AdoptBackend().
  bool Reopen(std::string* error);

  // Reopen in three steps, for a caller that must not wait for the device (the control loop,
  // whose reopen runs on a worker thread):
  // - Suspend (quick, under the caller's lock): every command is refused ("not open") and none
  //   reaches the backend until AdoptBackend;
  // - OpenBackend (slow, on any one thread, without the lock): opens the backend and reads
  //   where each axis stands; touches nothing but the backend, which no command reaches then;
  // - AdoptBackend (quick, under the lock, after OpenBackend returned): takes those positions
  //   and lets commands through again. Nothing moves in any of the three.
  struct BackendReopen {
    bool ok = false;
    std::string error;               // why the backend did not open, when !ok
    std::optional<double> pan_deg;   // [deg] where the device says the axis stands
    std::optional<double> tilt_deg;  // [deg]
  };
  void Suspend() { open_ = false; }
  BackendReopen OpenBackend();
  void AdoptBackend(const BackendReopen& reopened);
  bool SetAngle(ServoAxis axis, double deg, std::string* error) override;
  bool Park(std::string* error) override;
  std::string Describe() const override;

  // Steps both axes towards park_deg, each step one frame period's worth at the rate, calling
  // `wait_one_period` between steps, until AtPark() (true) or a command fails (false). Ends
  // within (max − min) / (rate · frame period) + 1 steps.
  bool ParkAndWait(const std::function<void()>& wait_one_period, std::string* error);

  bool AtPark() const;
  // Whether any axis has been put somewhere known since Open (a command, or a position read).
  bool placed() const { return pan_.placed || tilt_.placed; }
  double frame_period_s() const { return frame_period_s_; }
  // The largest step one command may make on `axis` [deg]: max_rate · frame period.
  double max_step_deg(ServoAxis axis) const;
  double angle(ServoAxis axis) const;  // [deg] last angle the backend accepted
  const ServoLimits& limits(ServoAxis axis) const;
  std::uint64_t refused_count() const { return refused_; }  // non-finite requests
  std::uint64_t limited_count() const { return limited_; }  // requests changed by the limits

 private:
  struct AxisState {
    ServoLimiter limiter;
    double angle_deg;
    std::int64_t commanded_at_us = 0;
    bool placed = false;  // a command has put the servo somewhere known since Open
  };

  AxisState& State(ServoAxis axis) { return axis == ServoAxis::kPan ? pan_ : tilt_; }
  const AxisState& State(ServoAxis axis) const { return axis == ServoAxis::kPan ? pan_ : tilt_; }
  bool StepTowardsPark(double dt_s, std::string* error);
  // dt_s: the time the step may cover [s]; NaN = measured since the last command.
  bool Command(ServoAxis axis, double target_deg, double dt_s, std::string* error);

  std::unique_ptr<ServoDriver> backend_;
  MonotonicClockUs clock_;
  double frame_period_s_;
  AxisState pan_;
  AxisState tilt_;
  bool open_ = false;
  std::uint64_t refused_ = 0;
  std::uint64_t limited_ = 0;
};

}  // namespace kapfix::agent
