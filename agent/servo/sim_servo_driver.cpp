#include "agent/servo/sim_servo_driver.hpp"

#include <stdexcept>

namespace kapfix::agent {

SimServoDriver::SimServoDriver(std::shared_ptr<SimulatedPlatform> platform)
    : platform_(std::move(platform)) {
  if (!platform_) throw std::invalid_argument("SimServoDriver: no platform");
}

bool SimServoDriver::Open(std::string* /*error*/) {
  open_ = true;
  return true;
}

bool SimServoDriver::SetAngle(ServoAxis axis, double deg, std::string* error) {
  if (!open_) {
    if (error) *error = Describe() + ": not open";
    return false;
  }
  if (axis == ServoAxis::kPan) {
    platform_->CommandPan(deg);
  } else {
    platform_->CommandTilt(deg);
  }
  return true;
}

bool SimServoDriver::Park(std::string* error) {
  return SetAngle(ServoAxis::kPan, 0.0, error) && SetAngle(ServoAxis::kTilt, 0.0, error);
}

}  // namespace kapfix::agent
