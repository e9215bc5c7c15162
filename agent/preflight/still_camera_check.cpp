#include "agent/preflight/still_camera_check.hpp"

namespace kapfix::agent {

PreflightCheck CheckStillCamera(StillCamera& camera) {
  const std::string what = "still camera (" + camera.Name() + ")";
  std::string model;
  StillCameraError error;
  if (camera.Open(&model, &error)) {
    camera.Close();
    return {.pass = true,
            .what = what,
            .detail = model + " found and opened (no photo taken)",
            .fix = ""};
  }
  std::string fix;
  switch (error.fault) {
    case StillCameraFault::kAbsent:
    case StillCameraFault::kVanished:
      fix =
          "connect the camera by USB, switch it on, set its USB mode to PTP (not mass "
          "storage), check `gphoto2 --auto-detect`; or --photo-camera agent";
      break;
    case StillCameraFault::kBusy:
      fix =
          "another program holds the camera (gvfs-gphoto2-volume-monitor, a file manager): "
          "stop it, or unplug and plug the camera";
      break;
    case StillCameraFault::kRefused:
      fix =
          "set the camera to PTP / remote capture mode; check that gphoto2 supports capture "
          "on this model (gphoto2 --summary)";
      break;
  }
  return {.pass = false, .what = what, .detail = error.message, .fix = fix};
}

}  // namespace kapfix::agent
