#include "agent/still_camera/still_camera.hpp"

namespace kapfix::agent {

std::string_view ToString(StillCameraFault fault) {
  switch (fault) {
    case StillCameraFault::kAbsent:
      return "absent";
    case StillCameraFault::kBusy:
      return "busy";
    case StillCameraFault::kRefused:
      return "refused";
    case StillCameraFault::kVanished:
      return "vanished";
  }
  return "unknown";
}

}  // namespace kapfix::agent
