#include "agent/capture/sim_frame_source.hpp"

#include <cmath>
#include <stdexcept>
#include <thread>

namespace kapfix::agent {
namespace {

constexpr std::size_t kTruthFrames = 1024;

}  // namespace

SimFrameSource::SimFrameSource(std::shared_ptr<SimulatedPlatform> platform, double fps,
                               bool real_time)
    : platform_(std::move(platform)), fps_(fps), real_time_(real_time) {
  if (!platform_) throw std::invalid_argument("SimFrameSource: no platform");
  if (!std::isfinite(fps_) || fps_ <= 0) throw std::invalid_argument("SimFrameSource: fps ≤ 0");
  using kapfix::v1::CameraSettings;
  controls_
      .Add(CameraSettings::kGainDbFieldNumber,
           [this](double db, std::string* reason) { return SetGain(db, reason); })
      .Add(CameraSettings::kAutoExposureFieldNumber,
           [this](double on, std::string* reason) { return SetAutoExposure(on != 0, reason); });
}

bool SimFrameSource::Open(std::string* /*error*/) {
  open_ = true;
  start_ = std::chrono::steady_clock::now();
  return true;
}

bool SimFrameSource::Grab(CapturedFrame* frame, std::string* error) {
  if (!open_) {
    if (error) *error = Describe() + ": not open";
    return false;
  }
  if (real_time_) {
    std::this_thread::sleep_until(start_ + std::chrono::microseconds(std::llround(
                                               static_cast<double>(next_index_) * 1e6 / fps_)));
  }
  if (next_index_ > 0) platform_->Step();
  // A frame the camera loses never arrives: the next one does, one frame period later.
  while (next_index_ > 0 && platform_->FrameDropped(platform_->frame())) {
    platform_->Step();
    ++next_index_;
    ++dropped_;
  }
  const SimulatedFrame captured = platform_->CaptureFrame();
  const cv::Point2d offset = platform_->ViewOffset();
  if (brightness_ == 1.0) {
    frame->image = captured.image;
  } else {
    // A new image: the platform's may be shared. Saturates at 255 as a sensor does.
    captured.image.convertTo(frame->image, -1, brightness_);
  }
  frame->index = next_index_;
  frame->capture_time_us =
      static_cast<std::int64_t>(std::llround(static_cast<double>(next_index_) * 1e6 / fps_));
  {
    std::lock_guard lock(truth_mutex_);
    truth_.emplace_back(next_index_, offset);
    if (truth_.size() > kTruthFrames) truth_.pop_front();
  }
  ++next_index_;
  return true;
}

bool SimFrameSource::Apply(const kapfix::v1::CameraSettings& settings, std::string* error) {
  return controls_.Apply(settings, Describe(), error);
}

bool SimFrameSource::SetGain(double db, std::string* reason) {
  if (!std::isfinite(db)) {
    if (reason) *reason = "not a finite number";
    return false;
  }
  brightness_ = std::pow(10.0, db / 20.0);  // gain [dB] of the signal's amplitude
  return true;
}

bool SimFrameSource::SetAutoExposure(bool on, std::string* reason) {
  if (on) return true;  // the simulated frames are the auto-exposed ones
  if (reason) *reason = "the simulated camera is always automatically exposed";
  return false;
}

std::string SimFrameSource::Describe() const {
  const cv::Size size = platform_->options().camera.frame_size;
  const bool boat = platform_->options().motion == SimulatedPlatformOptions::Motion::kBoat;
  return "sim camera " + std::to_string(size.width) + "x" + std::to_string(size.height) + " (" +
         (boat ? "boat" : "kite") + ")";
}

std::optional<cv::Point2d> SimFrameSource::ViewOffset(std::uint64_t index) const {
  std::lock_guard lock(truth_mutex_);
  for (auto it = truth_.rbegin(); it != truth_.rend(); ++it) {
    if (it->first == index) return it->second;
    if (it->first < index) break;
  }
  return std::nullopt;
}

}  // namespace kapfix::agent
