#include "agent/config/video_config.hpp"

#include <cmath>

namespace kapfix::agent {

bool VideoConfig::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (!std::isfinite(fps) || fps < 0 || fps > 120) {
    return fail("video.fps: must be 0…120 frames/s, got " + std::to_string(fps));
  }
  if (quality < 1 || quality > 100) {
    return fail("video.quality: must be 1…100, got " + std::to_string(quality));
  }
  if (!std::isfinite(scale) || scale <= 0 || scale > 1) {
    return fail("video.scale: must be in (0, 1], got " + std::to_string(scale));
  }
  return true;
}

}  // namespace kapfix::agent
