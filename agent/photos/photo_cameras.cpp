#include "agent/photos/photo_cameras.hpp"

#include <spdlog/spdlog.h>

#include <stdexcept>

namespace kapfix::agent {

void PhotoCameras::Select(kapfix::v1::PhotoCamera camera) {
  if (camera == kapfix::v1::PHOTO_CAMERA_UNSPECIFIED) return;
  std::lock_guard lock(mutex_);
  selected_ = camera;
}

kapfix::v1::PhotoCamera PhotoCameras::selected() const {
  std::lock_guard lock(mutex_);
  return selected_;
}

void PhotoCameras::SetStillCamera(std::shared_ptr<PhotoTrigger> still) {
  std::lock_guard lock(mutex_);
  still_ = std::move(still);
}

TakenPhoto PhotoCameras::Take(const PhotoRequest& request, kapfix::v1::PhotoMetadata* metadata) {
  TakenPhoto photo;
  std::string fallback_reason;
  bool still_selected = false;
  std::shared_ptr<PhotoTrigger> camera;
  {
    std::lock_guard lock(mutex_);
    still_selected = selected_ == kapfix::v1::PHOTO_CAMERA_GPHOTO2;
    if (still_selected) camera = still_;
  }
  if (camera) {
    if (!camera->Take(request, &photo, &fallback_reason) && fallback_reason.empty()) {
      fallback_reason = camera->Describe() + ": no photo, no reason given";
    }
  } else if (still_selected) {
    fallback_reason = "gphoto2: this agent has no still camera";
  }
  if (!still_selected || !fallback_reason.empty()) {
    std::string error;
    photo = TakenPhoto{};
    if (!agent_.Take(request, &photo, &error)) {
      throw std::runtime_error(fallback_reason.empty() ? error : fallback_reason + "; " + error);
    }
  }
  if (!fallback_reason.empty()) {
    spdlog::warn("photo {}: {}; taken with the agent's camera instead",
                 request.file_name.empty() ? std::string("(interval)") : request.file_name,
                 fallback_reason);
  }
  metadata->set_camera(photo.camera);
  metadata->set_camera_fallback_reason(fallback_reason);
  metadata->set_width_px(photo.width_px);
  metadata->set_height_px(photo.height_px);
  metadata->set_format(photo.format);
  return photo;
}

void PhotoCameras::Stored(const TakenPhoto& photo) {
  if (photo.camera != kapfix::v1::PHOTO_CAMERA_GPHOTO2) return;
  std::shared_ptr<PhotoTrigger> camera;
  {
    std::lock_guard lock(mutex_);
    camera = still_;  // the one that took it, even if the selection changed since
  }
  if (camera) camera->Stored(photo);
}

}  // namespace kapfix::agent
