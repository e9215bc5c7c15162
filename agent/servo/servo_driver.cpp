#include "agent/servo/servo_driver.hpp"

namespace kapfix::agent {

std::string_view ToString(ServoAxis axis) {
  switch (axis) {
    case ServoAxis::kPan:
      return "pan";
    case ServoAxis::kTilt:
      return "tilt";
  }
  return "?";
}

bool ServoDriver::ReadAngle(ServoAxis axis, double* /*deg*/, std::string* error) {
  if (error) *error = Describe() + ": cannot read the " + std::string(ToString(axis)) + " position";
  return false;
}

}  // namespace kapfix::agent
