#include "common/sim/simulated_platform.hpp"

#include <cmath>
#include <stdexcept>

#include "common/sim/sim_random.hpp"

namespace kapfix {
namespace {

constexpr std::uint64_t kDropStream = 0x64726f70;  // "drop"

const SimulatedPlatformOptions& Validated(const SimulatedPlatformOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument("SimulatedPlatform: " + error);
  return options;
}

std::unique_ptr<const PlatformMotion> MakeMotion(const SimulatedPlatformOptions& options) {
  if (options.motion == SimulatedPlatformOptions::Motion::kBoat) {
    return std::make_unique<BoatMotion>(options.boat);
  }
  return std::make_unique<KiteMotion>(options.kite);
}

}  // namespace

bool SimulatedPlatformOptions::IsValid(std::string* error) const {
  const bool motion_ok = motion == Motion::kBoat ? boat.IsValid(error) : kite.IsValid(error);
  if (!motion_ok || !camera.IsValid(error)) return false;
  if (!pan.IsValid(error) || !tilt.IsValid(error)) return false;
  if (!std::isfinite(px_per_deg) || px_per_deg <= 0) {
    if (error) *error = "px per degree must be > 0, got " + std::to_string(px_per_deg);
    return false;
  }
  if (!(frame_drop_rate >= 0 && frame_drop_rate <= 0.5)) {
    if (error) *error = "frame drop rate must be 0…0.5, got " + std::to_string(frame_drop_rate);
    return false;
  }
  return true;
}

SimulatedPlatform::SimulatedPlatform(const cv::Mat& scene_bgr, SimulatedPlatformOptions options)
    : options_(Validated(options)),
      camera_(scene_bgr, options_.camera),
      motion_(MakeMotion(options_)),
      pan_(options_.pan),
      tilt_(options_.tilt) {
  initial_line_of_sight_ = LineOfSightLocked();
  previous_line_of_sight_ = initial_line_of_sight_;
}

bool SimulatedPlatform::FrameDropped(int frame) const {
  return options_.frame_drop_rate > 0 && frame > 0 &&
         SimUniform(options_.camera.seed, kDropStream, frame) < options_.frame_drop_rate;
}

cv::Point2d SimulatedPlatform::LineOfSightLocked() const {
  const cv::Point2d servo(pan_.angle(), tilt_.angle());
  return motion_->LineOfSight(frame_) + servo * options_.px_per_deg;
}

SimulatedFrame SimulatedPlatform::CaptureFrame() const {
  SimulatedFrame out;
  cv::Point2d line_of_sight, motion;
  {
    std::lock_guard lock(mutex_);
    out.frame = frame_;
    out.pan_deg = pan_.angle();
    out.tilt_deg = tilt_.angle();
    line_of_sight = LineOfSightLocked();
    motion = line_of_sight - previous_line_of_sight_;
  }
  // SceneCamera::Capture is const and stateless: render without holding the lock, so that
  // commands from the control thread never wait for a frame to be drawn.
  out.image = camera_.Capture(out.frame, line_of_sight, motion);
  return out;
}

cv::Mat SimulatedPlatform::Capture() const { return CaptureFrame().image; }

void SimulatedPlatform::CommandPan(double deg) {
  std::lock_guard lock(mutex_);
  pan_.Command(deg);
}

void SimulatedPlatform::CommandTilt(double deg) {
  std::lock_guard lock(mutex_);
  tilt_.Command(deg);
}

void SimulatedPlatform::Step() {
  std::lock_guard lock(mutex_);
  previous_line_of_sight_ = LineOfSightLocked();
  pan_.Step();
  tilt_.Step();
  ++frame_;
}

int SimulatedPlatform::frame() const {
  std::lock_guard lock(mutex_);
  return frame_;
}

cv::Point2d SimulatedPlatform::LineOfSight() const {
  std::lock_guard lock(mutex_);
  return LineOfSightLocked();
}

cv::Point2d SimulatedPlatform::ViewOffset() const {
  std::lock_guard lock(mutex_);
  return LineOfSightLocked() - initial_line_of_sight_;
}

cv::Point2d SimulatedPlatform::OpenLoopOffset() const {
  std::lock_guard lock(mutex_);
  const cv::Point2d servo(options_.pan.initial_deg, options_.tilt.initial_deg);
  return motion_->LineOfSight(frame_) + servo * options_.px_per_deg - initial_line_of_sight_;
}

double SimulatedPlatform::pan_deg() const {
  std::lock_guard lock(mutex_);
  return pan_.angle();
}

double SimulatedPlatform::tilt_deg() const {
  std::lock_guard lock(mutex_);
  return tilt_.angle();
}

}  // namespace kapfix
