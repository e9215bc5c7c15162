#include "agent/config/camera_config.hpp"

#include <cmath>

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
  if (gain_db && (!std::isfinite(*gain_db) || std::abs(*gain_db) > 1000)) {
    return fail("camera.gain_db: must be finite and within ±1000, got " + std::to_string(*gain_db));
  }
  if (exposure_us && (!std::isfinite(*exposure_us) || *exposure_us <= 0 || *exposure_us > 10e6)) {
    return fail("camera.exposure_us: must be in (0, 1e7] µs, got " + std::to_string(*exposure_us));
  }
  std::string reason;
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
