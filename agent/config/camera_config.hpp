#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "agent/capture/aravis_frame_source.hpp"
#include "agent/capture/v4l2_frame_source.hpp"

namespace kapfix::agent {

enum class CameraBackend {
  kSim,     // the simulated scene camera (SPEC §3)
  kV4l2,    // V4L2/UVC through OpenCV
  kAravis,  // GenICam (USB3 Vision, GigE Vision) through Aravis
};

std::optional<CameraBackend> ParseCameraBackend(std::string_view text);  // sim|v4l2|aravis
std::string_view ToString(CameraBackend backend);

// The "camera" section. Defaults: resources/README.md.
struct CameraConfig {
  CameraBackend backend = CameraBackend::kSim;
  // v4l2: path or index ("" = /dev/video0); aravis: device id ("" = first camera); sim: unused.
  std::string device;
  int width = 640;   // [px]
  int height = 480;  // [px]
  double fps = 30;   // [frames/s]
  // v4l2: fourcc ("MJPG", "YUYV"); aravis: GenICam pixel format ("Mono8", "BayerRG8");
  // "" = the camera's current setting.
  std::string format;
  std::optional<double> gain_db;      // [dB] (v4l2: the driver's unit); unset = leave as is
  std::optional<double> exposure_us;  // [µs] unset = leave the camera's (auto) exposure

  bool IsValid(std::string* error) const;

  V4l2FrameSourceOptions ToV4l2Options() const;
  AravisFrameSourceOptions ToAravisOptions() const;
};

}  // namespace kapfix::agent
