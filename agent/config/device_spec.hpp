#pragma once

#include <string>
#include <string_view>

#include "agent/config/camera_config.hpp"
#include "agent/config/servo_config.hpp"

namespace kapfix::agent {

// `--camera SPEC` and `--servos SPEC`: one device named on the command line, overriding the
// configuration's backend and device, so that one command tries a device (issue 10).
//   camera: sim | v4l2:/dev/video0 | v4l2:0 | aravis | aravis:ID-or-address
//   servos: sim | maestro:/dev/kapfix-maestro | pca9685:/dev/i2c-1 | pca9685:/dev/i2c-1@0x40
// Everything else in the section (size, fps, mapping, limits) stays as configured.
// False with a one-line reason naming the spec and the accepted forms; nothing is changed then.
bool ApplyCameraSpec(std::string_view spec, CameraConfig* camera, std::string* error);
bool ApplyServoSpec(std::string_view spec, ServoConfig* servo, std::string* error);

}  // namespace kapfix::agent
