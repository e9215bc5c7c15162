#pragma once

#include <string>
#include <string_view>

namespace kapfix::agent {

enum class ServoAxis { kPan, kTilt };

std::string_view ToString(ServoAxis axis);

// The seam between the control loop and the servo hardware (SPEC §4). Angles are relative to
// each axis's centre [deg]. Backends translate angles into pulses and nothing else; limits
// and rate limits are enforced for every backend in one place, LimitedServoDriver, which the
// agent always puts in front of a backend.
//
// Methods return false with a reason naming the device when the hardware does not do what
// was asked; they never throw for a missing or failing device.
class ServoDriver {
 public:
  virtual ~ServoDriver() = default;
  // Opens the device; does not move the servos.
  virtual bool Open(std::string* error) = 0;
  virtual bool SetAngle(ServoAxis axis, double deg, std::string* error) = 0;
  // Moves both axes to their hold position and keeps them there (a backend: 0 deg, each
  // channel's centre pulse; LimitedServoDriver: ServoLimits::park_deg, rate-limited).
  virtual bool Park(std::string* error) = 0;
  // Where the servo on `axis` stands now [deg], read from the device (a Maestro's Get
  // Position). False where the device cannot tell (the default): the caller then keeps what
  // it last commanded. Used after an outage, when the device may have moved the servos on its
  // own (a Maestro's serial timeout sends them home).
  virtual bool ReadAngle(ServoAxis axis, double* deg, std::string* error);
  // One line for logs and the station, e.g. "maestro /dev/ttyACM0 (pan ch 0, tilt ch 1)".
  virtual std::string Describe() const = 0;
};

}  // namespace kapfix::agent
