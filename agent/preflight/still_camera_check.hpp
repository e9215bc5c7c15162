#pragma once

#include "agent/preflight/preflight.hpp"
#include "agent/still_camera/still_camera.hpp"

namespace kapfix::agent {

// The preflight line of the still camera (when the photo camera is gphoto2): it is found and
// opens; nothing is captured. On failure, the fix for that kind of fault.
PreflightCheck CheckStillCamera(StillCamera& camera);

}  // namespace kapfix::agent
