#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "agent/capture/aravis_frame_source.hpp"
#include "agent/capture/v4l2_frame_source.hpp"
#include "kapfix/v1/settings.pb.h"
#include "kapfix/v1/settings_schema.hpp"

namespace kapfix::agent {

enum class CameraBackend {
  kSim,     // the simulated scene camera (SPEC §3)
  kV4l2,    // V4L2/UVC through OpenCV
  kAravis,  // GenICam (USB3 Vision, GigE Vision) through Aravis
};

std::optional<CameraBackend> ParseCameraBackend(std::string_view text);  // sim|v4l2|aravis
std::string_view ToString(CameraBackend backend);

// A settings command's camera fields merged into the held ones (MergeSettings), where a fixed
// exposure and automatic exposure exclude each other: the later one counts, and automatic
// exposure switched off alone changes nothing (there is no exposure to fall back to).
void MergeCameraSettings(const kapfix::v1::CameraSettings& from, kapfix::v1::CameraSettings* into);

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
  // The operator's gain and exposure as their kapfix.v1 message: a field unset leaves the
  // camera's own (its gain, its automatic exposure); v4l2 takes the gain in the driver's unit.
  kapfix::v1::CameraSettings settings = kapfix::v1::InitialSettings<kapfix::v1::CameraSettings>();

  bool IsValid(std::string* error) const;

  V4l2FrameSourceOptions ToV4l2Options() const;
  AravisFrameSourceOptions ToAravisOptions() const;
};

}  // namespace kapfix::agent
