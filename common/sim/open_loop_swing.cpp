#include "common/sim/open_loop_swing.hpp"

#include <stdexcept>
#include <utility>

namespace kapfix {
namespace {

const SwingOptions& Validated(const SwingOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument("OpenLoopSwing: " + error);
  return options;
}

}  // namespace

bool SwingOptions::IsValid(std::string* error) const {
  if (!camera.IsValid(error) || !motion.IsValid(error)) return false;
  if (frames < 1) {
    if (error) *error = "swing needs at least 1 frame, got " + std::to_string(frames);
    return false;
  }
  if (motion.amplitude_px > camera.max_excursion_px) {
    if (error) {
      *error = "swing amplitude " + std::to_string(motion.amplitude_px) +
               " px exceeds the camera's max excursion " + std::to_string(camera.max_excursion_px) +
               " px";
    }
    return false;
  }
  return true;
}

SwingOptions SwingOptions::ForFrameSize(cv::Size frame_size) {
  SwingOptions options;
  options.camera.frame_size = frame_size;
  return options;
}

OpenLoopSwing::OpenLoopSwing(const cv::Mat& scene_bgr, SwingOptions options)
    : options_(Validated(options)), camera_(scene_bgr, options_.camera), motion_(options_.motion) {}

cv::Mat OpenLoopSwing::Frame(int t) const {
  if (t < 0 || t >= options_.frames) {
    throw std::out_of_range("OpenLoopSwing::Frame: frame " + std::to_string(t) + " outside 0…" +
                            std::to_string(options_.frames - 1));
  }
  return camera_.Capture(t, motion_.LineOfSight(t));
}

cv::Point2d OpenLoopSwing::LineOfSight(int t) const { return motion_.LineOfSight(t); }

cv::Point2d OpenLoopSwing::TrueDisplacement(int t, int reference_frame) const {
  return -(motion_.LineOfSight(t) - motion_.LineOfSight(reference_frame));
}

}  // namespace kapfix
