#include "agent/photos/photo_quality.hpp"

#include <cmath>
#include <limits>

#include "common/image/sharpness.hpp"

namespace kapfix::agent {

void FillShotQuality(const ShutterShot& shot, ShutterMode mode, double exposure_ms,
                     kapfix::v1::PhotoMetadata* metadata) {
  metadata->set_residual_offset_px(static_cast<float>(shot.offset_px));
  metadata->set_view_speed_px_per_frame(static_cast<float>(shot.speed_px_per_frame));
  metadata->set_view_blur_px(static_cast<float>(shot.blur_px));
  metadata->set_lock_lost(shot.lock_lost);
  metadata->set_shutter(mode == ShutterMode::kBestPhase ? kapfix::v1::SHUTTER_BEST_PHASE
                                                        : kapfix::v1::SHUTTER_INTERVAL);
  metadata->set_shutter_wait_s(static_cast<float>(shot.wait_s));
  metadata->set_shutter_reason(shot.reason);
  metadata->set_exposure_ms(static_cast<float>(exposure_ms));
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

PhotoFigures ComputePhotoFigures(const std::vector<kapfix::v1::PhotoMetadata>& photos) {
  PhotoFigures f;
  f.photos = photos.size();
  if (photos.empty()) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    f.view_speed_px_mean = f.view_blur_px_mean = f.offset_px_mean = f.sharpness_mean =
        f.wait_s_mean = f.lock_lost_share = nan;
    return f;
  }
  for (const auto& p : photos) {
    f.view_speed_px_mean += p.view_speed_px_per_frame();
    f.view_blur_px_mean += p.view_blur_px();
    f.offset_px_mean += p.residual_offset_px();
    f.sharpness_mean += p.sharpness_frame();
    f.wait_s_mean += p.shutter_wait_s();
    f.lock_lost_share += p.lock_lost() ? 1.0 : 0.0;
  }
  const auto n = static_cast<double>(photos.size());
  f.view_speed_px_mean /= n;
  f.view_blur_px_mean /= n;
  f.offset_px_mean /= n;
  f.sharpness_mean /= n;
  f.wait_s_mean /= n;
  f.lock_lost_share /= n;
  return f;
}

}  // namespace kapfix::agent
