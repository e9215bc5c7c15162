#include "agent/capture/v4l2_frame_source.hpp"

#include <spdlog/spdlog.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <opencv2/imgproc.hpp>
#include <thread>

#include "common/time/steady_clock.hpp"

namespace kapfix::agent {
namespace {

bool IsIndex(const std::string& text) {
  return !text.empty() && text.size() <= 3 &&
         std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isdigit(c); });
}

// V4L2_CID_EXPOSURE_ABSOLUTE counts in units of 100 µs.
constexpr double kV4l2ExposureUnitUs = 100;
// V4L2_EXPOSURE_MANUAL in enum v4l2_exposure_auto_type.
constexpr double kV4l2ExposureManual = 1;
// V4L2_EXPOSURE_APERTURE_PRIORITY: automatic exposure time, the automatic mode UVC webcams have
// (V4L2_EXPOSURE_AUTO, 0, also sets the iris, which they do not have).
constexpr double kV4l2ExposureAuto = 3;

bool Refuse(const std::string& what, std::string* reason) {
  if (reason) *reason = what;
  return false;
}

}  // namespace

bool V4l2FrameSourceOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (device.empty()) return fail("V4L2 device is empty");
  if (width < 16 || width > 8192 || height < 16 || height > 8192) {
    return fail("V4L2 frame size must be 16…8192 px per side, got " + std::to_string(width) + "x" +
                std::to_string(height));
  }
  if (!std::isfinite(fps) || fps <= 0 || fps > 1000) {
    return fail("V4L2 fps must be in (0, 1000], got " + std::to_string(fps));
  }
  if (grab_timeout_ms < 1 || grab_timeout_ms > 60000) {
    return fail("V4L2 grab_timeout_ms must be 1…60000, got " + std::to_string(grab_timeout_ms));
  }
  if (!fourcc.empty() && fourcc.size() != 4) {
    return fail("V4L2 fourcc must be 4 characters (e.g. MJPG), got '" + fourcc + "'");
  }
  return true;
}

V4l2FrameSource::V4l2FrameSource(V4l2FrameSourceOptions options) : options_(std::move(options)) {
  using kapfix::v1::CameraSettings;
  controls_
      .Add(CameraSettings::kGainDbFieldNumber,
           [this](double value, std::string* reason) { return SetGain(value, reason); })
      .Add(CameraSettings::kExposureUsFieldNumber,
           [this](double us, std::string* reason) { return SetExposure(us, reason); })
      .Add(CameraSettings::kAutoExposureFieldNumber,
           [this](double on, std::string* reason) { return SetAutoExposure(on != 0, reason); });
}

std::string V4l2FrameSource::DevicePath() const {
  return IsIndex(options_.device) ? "/dev/video" + options_.device : options_.device;
}

bool V4l2FrameSource::Fail(const std::string& reason, std::string* error) const {
  if (error) *error = "V4L2 camera " + DevicePath() + ": " + reason;
  return false;
}

bool V4l2FrameSource::Open(std::string* error) {
  capture_.release();
  next_index_ = 0;
  std::string reason;
  if (!options_.IsValid(&reason)) return Fail(reason, error);
  const std::string path = DevicePath();
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) {
    const int code = errno;
    if (code == ENOENT) return Fail("no such device (camera unplugged?)", error);
    return Fail("cannot inspect (" + std::string(std::strerror(code)) + ")", error);
  }
  if (!S_ISCHR(info.st_mode)) return Fail("not a video device (not a character device)", error);
  if (::access(path.c_str(), R_OK | W_OK) != 0) {
    return Fail("permission denied; is the agent's user in group video?", error);
  }
  // OpenCV reads this once, at its first V4L2 capture: set it before any open (0 = do not
  // replace an operator's own setting).
  const int timeout_s = std::max(1, (options_.grab_timeout_ms + 999) / 1000);
  ::setenv("OPENCV_VIDEOIO_V4L_SELECT_TIMEOUT", std::to_string(timeout_s).c_str(), 0);
  if (!capture_.open(path, cv::CAP_V4L2) || !capture_.isOpened()) {
    capture_.release();
    return Fail("OpenCV's V4L2 backend cannot open it (not a capture device, or busy?)", error);
  }
  if (!options_.fourcc.empty()) {
    const std::string& f = options_.fourcc;
    capture_.set(cv::CAP_PROP_FOURCC, cv::VideoWriter::fourcc(f[0], f[1], f[2], f[3]));
  }
  capture_.set(cv::CAP_PROP_FRAME_WIDTH, options_.width);
  capture_.set(cv::CAP_PROP_FRAME_HEIGHT, options_.height);
  capture_.set(cv::CAP_PROP_FPS, options_.fps);
  capture_.set(cv::CAP_PROP_BUFFERSIZE, 1);
  const double width = capture_.get(cv::CAP_PROP_FRAME_WIDTH);
  const double height = capture_.get(cv::CAP_PROP_FRAME_HEIGHT);
  const double fps = capture_.get(cv::CAP_PROP_FPS);
  if (width != options_.width || height != options_.height || std::abs(fps - options_.fps) > 0.5) {
    spdlog::warn("V4L2 camera {}: asked for {}x{} @ {:g} fps, the driver gives {:g}x{:g} @ {:g}",
                 path, options_.width, options_.height, options_.fps, width, height, fps);
  }
  spdlog::info("camera: {} open", Describe());
  return true;
}

bool V4l2FrameSource::Grab(CapturedFrame* frame, std::string* error) {
  if (!capture_.isOpened()) return Fail("not open", error);
  cv::Mat image;
  const std::int64_t deadline = SteadyClockNowUs() + std::int64_t{options_.grab_timeout_ms} * 1000;
  // A read interrupted by a signal (EINTR) fails at once: try again until the deadline.
  while (!capture_.read(image) || image.empty()) {
    if (SteadyClockNowUs() >= deadline || !capture_.isOpened()) {
      return Fail("lost (no frame within " + std::to_string(options_.grab_timeout_ms) +
                      " ms; unplugged or stalled)",
                  error);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));  // no busy loop when it fails fast
  }
  const std::int64_t now = SteadyClockNowUs();
  // The driver's timestamp of the buffer [ms], CLOCK_MONOTONIC for UVC and most drivers.
  const auto driver_us = static_cast<std::int64_t>(capture_.get(cv::CAP_PROP_POS_MSEC) * 1000.0);
  const bool driver_stamp = driver_us > 0 && driver_us <= now && now - driver_us < 1'000'000;
  if (stamp_source_logged_ != (driver_stamp ? 1 : 2)) {
    stamp_source_logged_ = driver_stamp ? 1 : 2;
    spdlog::info("V4L2 camera {}: frames stamped {}", DevicePath(),
                 driver_stamp ? "by the driver (buffer timestamp, monotonic clock)"
                              : "on arrival (the driver's timestamp is not on the monotonic "
                                "clock)");
  }
  if (image.type() == CV_8UC1) {
    cv::cvtColor(image, frame->image, cv::COLOR_GRAY2BGR);
  } else if (image.type() == CV_8UC3) {
    frame->image = image;  // OpenCV copies the driver buffer into `image`: ours to keep
  } else {
    return Fail("unsupported frame type " + std::to_string(image.type()) + " (want 8-bit BGR)",
                error);
  }
  frame->capture_time_us = driver_stamp ? driver_us : now;
  frame->index = next_index_++;
  return true;
}

bool V4l2FrameSource::Apply(const kapfix::v1::CameraSettings& settings, std::string* error) {
  if (!capture_.isOpened()) return Fail("not open", error);
  return controls_.Apply(settings, "V4L2 camera " + DevicePath(), error);
}

bool V4l2FrameSource::SetGain(double value, std::string* reason) {
  if (!std::isfinite(value)) return Refuse("not a finite number", reason);
  if (!capture_.set(cv::CAP_PROP_GAIN, value)) {
    return Refuse("the driver refused it (no gain control, or out of its range)", reason);
  }
  return true;
}

bool V4l2FrameSource::SetExposure(double us, std::string* reason) {
  if (!std::isfinite(us) || us <= 0) return Refuse("must be > 0 µs", reason);
  if (!capture_.set(cv::CAP_PROP_AUTO_EXPOSURE, kV4l2ExposureManual)) {
    return Refuse("the driver refused manual exposure", reason);
  }
  const double units = std::max(1.0, std::round(us / kV4l2ExposureUnitUs));
  if (!capture_.set(cv::CAP_PROP_EXPOSURE, units)) return Refuse("the driver refused it", reason);
  return true;
}

bool V4l2FrameSource::SetAutoExposure(bool on, std::string* reason) {
  if (!capture_.set(cv::CAP_PROP_AUTO_EXPOSURE, on ? kV4l2ExposureAuto : kV4l2ExposureManual)) {
    return Refuse(
        on ? "the driver has no automatic exposure" : "the driver refused manual exposure", reason);
  }
  return true;
}

std::string V4l2FrameSource::Describe() const {
  return "v4l2 " + DevicePath() + " " + std::to_string(options_.width) + "x" +
         std::to_string(options_.height) + " @ " + fmt::format("{:g}", options_.fps) + " fps";
}

}  // namespace kapfix::agent
