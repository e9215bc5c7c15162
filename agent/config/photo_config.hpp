#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "common/shutter/best_phase_shutter.hpp"

namespace kapfix::agent {

// Which camera takes the photos (issue 13).
enum class PhotoCameraKind { kAgent, kGphoto2 };

// The "photos" section: stabilised full-resolution photos, saved on the agent's disk first
// (SPEC §4), and when the shutter fires (issue 13). Defaults: resources/README.md.
struct PhotoConfig {
  std::string dir = "/var/lib/kapfix/photos";  // created if missing
  double interval_s = 0;                       // [s] automatic photo period; 0 = on command only
  ShutterMode shutter = ShutterMode::kInterval;
  double window_s = 0;       // [s] best-phase wait for the quietest moment; 0 = one swing period
  double window_cap_s = 10;  // [s] longest best-phase wait; a longer window is refused
  double exposure_ms = 10;   // [ms] exposure the shutter plans for (and the simulation blurs)
  PhotoCameraKind camera = PhotoCameraKind::kAgent;

  // A directory, an interval of 0 or in the schema's range, window, cap and exposure in the
  // schema's ranges (PhotoSettings), and the window not longer than the cap.
  bool IsValid(std::string* error) const;
};

// "interval" or "best-phase" (the settings schema's words); nothing for another.
std::optional<ShutterMode> ParseShutterMode(std::string_view text);
std::string_view ToString(ShutterMode mode);
// "agent" or "gphoto2"; nothing for another.
std::optional<PhotoCameraKind> ParsePhotoCameraKind(std::string_view text);
std::string_view ToString(PhotoCameraKind camera);

}  // namespace kapfix::agent
