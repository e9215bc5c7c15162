#include "agent/servo/fake_servo_driver.hpp"

namespace kapfix::agent {

bool FakeServoDriver::Open(std::string* error) {
  if (fail_open_) {
    if (error) *error = "fake servos: open failed (as told)";
    return false;
  }
  open_ = true;
  ++open_count_;
  return true;
}

bool FakeServoDriver::CommandFails(std::string* error) {
  if (!open_) {
    if (error) *error = "fake servos: not open";
    return true;
  }
  if (fail_commands_ > 0) {
    --fail_commands_;
    if (error) *error = "fake servos: command failed (as told)";
    return true;
  }
  return false;
}

bool FakeServoDriver::SetAngle(ServoAxis axis, double deg, std::string* error) {
  if (CommandFails(error)) return false;
  commands_.push_back({FakeServoCommand::Kind::kSetAngle, axis, deg});
  (axis == ServoAxis::kPan ? pan_deg_ : tilt_deg_) = deg;
  return true;
}

bool FakeServoDriver::Park(std::string* error) {
  if (CommandFails(error)) return false;
  commands_.push_back({FakeServoCommand::Kind::kPark, ServoAxis::kPan, 0});
  pan_deg_ = 0;
  tilt_deg_ = 0;
  return true;
}

bool FakeServoDriver::ReadAngle(ServoAxis axis, double* deg, std::string* error) {
  if (!open_ || !readable_) {
    if (error) *error = "fake servos: position not readable";
    return false;
  }
  *deg = angle(axis);
  return true;
}

double FakeServoDriver::angle(ServoAxis axis) const {
  return axis == ServoAxis::kPan ? pan_deg_ : tilt_deg_;
}

}  // namespace kapfix::agent
