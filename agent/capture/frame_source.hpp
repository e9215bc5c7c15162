#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>

#include "kapfix/v1/settings.pb.h"

namespace kapfix::agent {

struct CapturedFrame {
  cv::Mat image;                     // BGR, CV_8UC3, owned by the frame (not a driver buffer)
  std::int64_t capture_time_us = 0;  // [µs] std::chrono::steady_clock when the frame arrived
  std::uint64_t index = 0;           // 0, 1, 2 … frames delivered since Open
};

// The seam between the camera and the fixation loop (SPEC §4): the simulated scene camera,
// V4L2/UVC through OpenCV, GenICam through Aravis, or a fake in tests.
//
// Methods return false with a reason naming the camera when the hardware does not do what
// was asked; they never throw for a missing or lost camera. After Grab fails on a lost
// camera, Open may be called again to reconnect (the agent retries with back-off).
class FrameSource {
 public:
  virtual ~FrameSource() = default;
  virtual bool Open(std::string* error) = 0;
  // Waits for the next frame; false + reason on a lost camera.
  virtual bool Grab(CapturedFrame* frame, std::string* error) = 0;
  // The operator's camera settings: every field set is applied (a field left unset leaves the
  // camera's own), each in the unit the message gives it; see each backend for what its camera
  // understands. False + one line naming the camera and each setting it refused or does not
  // have (CameraSettingControls); the others are still applied.
  virtual bool Apply(const kapfix::v1::CameraSettings& settings, std::string* error) = 0;
  // One line for logs and the station, e.g. "v4l2 /dev/video0 640x480 @ 30 fps".
  virtual std::string Describe() const = 0;
};

}  // namespace kapfix::agent
