// AravisFrameSourceOptions::IsValid, shared by the Aravis backend and its stub.
#include <cmath>

#include "agent/capture/aravis_frame_source.hpp"

namespace kapfix::agent {

bool AravisFrameSourceOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if ((width == 0) != (height == 0)) return fail("Aravis width and height must both be 0 or set");
  if (width != 0 && (width < 16 || width > 16384 || height < 16 || height > 16384)) {
    return fail("Aravis frame size must be 16…16384 px per side, got " + std::to_string(width) +
                "x" + std::to_string(height));
  }
  if (!std::isfinite(fps) || fps < 0 || fps > 1000) {
    return fail("Aravis fps must be 0 (camera's) or in (0, 1000], got " + std::to_string(fps));
  }
  if (grab_timeout_ms < 1 || grab_timeout_ms > 60000) {
    return fail("Aravis grab_timeout_ms must be 1…60000, got " + std::to_string(grab_timeout_ms));
  }
  if (buffers < 2 || buffers > 64) {
    return fail("Aravis buffers must be 2…64, got " + std::to_string(buffers));
  }
  return true;
}

}  // namespace kapfix::agent
