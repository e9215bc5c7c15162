#include "agent/config/camera_config.hpp"

#include <cmath>

#include "kapfix/v1/settings.pb.h"
#include "kapfix/v1/settings_schema.hpp"

namespace kapfix::agent {

std::optional<CameraBackend> ParseCameraBackend(std::string_view text) {
  if (text == "sim") return CameraBackend::kSim;
  if (text == "v4l2") return CameraBackend::kV4l2;
  if (text == "aravis") return CameraBackend::kAravis;
  return std::nullopt;
}

std::string_view ToString(CameraBackend backend) {
  switch (backend) {
    case CameraBackend::kSim:
      return "sim";
    case CameraBackend::kV4l2:
      return "v4l2";
    case CameraBackend::kAravis:
      return "aravis";
  }
  return "?";
}

void MergeCameraSettings(const kapfix::v1::CameraSettings& from, kapfix::v1::CameraSettings* into) {
  kapfix::v1::CameraSettings update = from;
  if (update.has_auto_exposure() && !update.auto_exposure()) update.clear_auto_exposure();
  if (update.has_auto_exposure()) {
    update.clear_exposure_us();  // both in one command: automatic, as the later word
    into->clear_exposure_us();
  }
  if (update.has_exposure_us()) into->clear_auto_exposure();
  kapfix::v1::MergeSettings(update, into);
}

bool CameraConfig::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (width < 16 || width > 8192) {
    return fail("camera.width: must be 16…8192 px, got " + std::to_string(width));
  }
  if (height < 16 || height > 8192) {
    return fail("camera.height: must be 16…8192 px, got " + std::to_string(height));
  }
  if (!std::isfinite(fps) || fps <= 0 || fps > 1000) {
    return fail("camera.fps: must be in (0, 1000], got " + std::to_string(fps));
  }
  // The ranges are the schema's (kapfix.v1.CameraSettings), shared with the command validator.
  std::string reason = kapfix::v1::CheckSettings(settings, "camera");
  if (!reason.empty()) return fail(reason);
  if (backend == CameraBackend::kV4l2 && !ToV4l2Options().IsValid(&reason)) {
    return fail("camera: " + reason);
  }
  if (backend == CameraBackend::kAravis && !ToAravisOptions().IsValid(&reason)) {
    return fail("camera: " + reason);
  }
  return true;
}

V4l2FrameSourceOptions CameraConfig::ToV4l2Options() const {
  V4l2FrameSourceOptions o;
  if (!device.empty()) o.device = device;
  o.width = width;
  o.height = height;
  o.fps = fps;
  o.fourcc = format;
  return o;
}

AravisFrameSourceOptions CameraConfig::ToAravisOptions() const {
  AravisFrameSourceOptions o;
  o.camera_id = device;
  o.width = width;
  o.height = height;
  o.fps = fps;
  o.pixel_format = format;
  return o;
}

}  // namespace kapfix::agent
