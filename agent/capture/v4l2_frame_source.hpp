#pragma once

#include <opencv2/videoio.hpp>
#include <string>

#include "agent/capture/camera_setting_controls.hpp"
#include "agent/capture/frame_source.hpp"

namespace kapfix::agent {

struct V4l2FrameSourceOptions {
  std::string device = "/dev/video0";  // a path, or an index ("0" means /dev/video0)
  int width = 640;                     // [px] requested; the driver may pick the nearest
  int height = 480;                    // [px]
  double fps = 30;                     // [frames/s] requested
  std::string fourcc;                  // "" = driver default, else e.g. "MJPG" or "YUYV"
  // [ms] longest one Grab waits for a frame (a stalled camera is then reported lost and
  // reopened, instead of OpenCV's 10 s select()). OpenCV's V4L2 backend takes its select()
  // timeout in whole seconds from OPENCV_VIDEOIO_V4L_SELECT_TIMEOUT, read once per process:
  // Open sets it (unless the environment already does) to this, rounded up to seconds.
  int grab_timeout_ms = 1000;

  bool IsValid(std::string* error) const;
};

// A V4L2/UVC camera through OpenCV's V4L2 backend (cv::CAP_V4L2).
//
// Open checks the device node itself first (missing, not a character device, no permission)
// so that the reason is ours rather than an OpenCV warning, asks for size, fps and a one-frame
// driver queue (a stale frame is worse than none for the control loop), and logs what the
// driver granted where it differs.
//
// Camera settings: OpenCV passes CAP_PROP_* values to V4L2 unchanged. A fixed exposure [µs]
// turns auto exposure off (V4L2_EXPOSURE_MANUAL = 1) and writes V4L2_CID_EXPOSURE_ABSOLUTE,
// whose unit is 100 µs, so the value is converted; automatic exposure is
// V4L2_EXPOSURE_APERTURE_PRIORITY (3). The gain writes V4L2_CID_GAIN, whose unit the driver
// defines (UVC webcams: a 0…255 index, not dB); the value is passed as it is — read the
// camera's range with `v4l2-ctl -d DEV --list-ctrls`.
//
// Grab retries a failed read (a signal interrupting OpenCV's select() or ioctl, EINTR) until
// grab_timeout_ms, and only then reports the camera lost. Frames carry the driver's buffer
// timestamp (CLOCK_MONOTONIC, the clock of std::chrono::steady_clock on Linux, through
// CAP_PROP_POS_MSEC) when it is plausible (not in the future, under a second old), else the
// time of arrival; which one is said once in the log.
class V4l2FrameSource : public FrameSource {
 public:
  explicit V4l2FrameSource(V4l2FrameSourceOptions options);
  V4l2FrameSource(const V4l2FrameSource&) = delete;  // its controls point at it
  V4l2FrameSource& operator=(const V4l2FrameSource&) = delete;

  bool Open(std::string* error) override;
  bool Grab(CapturedFrame* frame, std::string* error) override;
  // Fails "not open" before Open.
  bool Apply(const kapfix::v1::CameraSettings& settings, std::string* error) override;
  std::string Describe() const override;

  // "/dev/videoN" for an index, the path otherwise.
  std::string DevicePath() const;

 private:
  bool Fail(const std::string& reason, std::string* error) const;
  // The controls: false + the reason the driver refused.
  bool SetGain(double value, std::string* reason);
  bool SetExposure(double us, std::string* reason);
  bool SetAutoExposure(bool on, std::string* reason);

  V4l2FrameSourceOptions options_;
  cv::VideoCapture capture_;
  std::uint64_t next_index_ = 0;
  int stamp_source_logged_ = 0;  // 0 none yet, 1 driver, 2 arrival
  CameraSettingControls controls_;
};

}  // namespace kapfix::agent
