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

}  // namespace kapfix::agent
