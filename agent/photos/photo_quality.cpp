#include "agent/photos/photo_quality.hpp"

#include <cmath>

#include "common/image/sharpness.hpp"

namespace kapfix::agent {

void FillShotQuality(const ShutterShot& shot, kapfix::v1::PhotoMetadata* metadata) {
  metadata->set_residual_offset_px(static_cast<float>(shot.offset_px));
  metadata->set_view_speed_px_per_frame(static_cast<float>(shot.speed_px_per_frame));
  metadata->set_view_blur_px(static_cast<float>(shot.blur_px));
  metadata->set_lock_lost(shot.lock_lost);
  metadata->set_shutter(shot.mode == ShutterMode::kBestPhase ? kapfix::v1::SHUTTER_BEST_PHASE
                                                             : kapfix::v1::SHUTTER_INTERVAL);
  metadata->set_shutter_wait_s(static_cast<float>(shot.wait_s));
  metadata->set_shutter_reason(shot.reason);
  metadata->set_exposure_ms(static_cast<float>(shot.exposure_ms));
  metadata->set_camera(kapfix::v1::PHOTO_CAMERA_AGENT);
}

cv::Rect PatchInFrame(cv::Rect patch, cv::Point2d displacement) {
  return patch + cv::Point(static_cast<int>(std::lround(displacement.x)),
                           static_cast<int>(std::lround(displacement.y)));
}

void FillSharpness(const cv::Mat& image, cv::Rect patch, kapfix::v1::PhotoMetadata* metadata) {
  const double frame = LaplacianVariance(image);
  metadata->set_sharpness_frame(static_cast<float>(frame));
  metadata->set_sharpness_patch(
      static_cast<float>(patch.empty() ? frame : LaplacianVariance(image, patch)));
}

}  // namespace kapfix::agent
