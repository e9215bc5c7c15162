#include "agent/config/photo_config.hpp"

#include <tuple>

#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/settings.pb.h"
#include "kapfix/v1/settings_schema.hpp"

namespace kapfix::agent {

bool PhotoConfig::IsValid(std::string* error) const {
  auto fail = [error](std::string message) {
    if (error) *error = std::move(message);
    return false;
  };
  if (dir.empty()) return fail("photos.dir: must not be empty");
  // The ranges are the schema's (Command.set_photo_interval_s, PhotoSettings).
  std::string reason = kapfix::v1::CheckSetting(
      *kapfix::v1::Command::descriptor(), "set_photo_interval_s", interval_s, "photos.interval_s");
  if (!reason.empty()) return fail(std::move(reason));
  const auto& settings = *kapfix::v1::PhotoSettings::descriptor();
  for (const auto& [field, value, shown] :
       {std::tuple{"window_s", window_s, "photos.window_s"},
        std::tuple{"window_cap_s", window_cap_s, "photos.window_cap_s"},
        std::tuple{"exposure_ms", exposure_ms, "photos.exposure_ms"}}) {
    reason = kapfix::v1::CheckSetting(settings, field, value, shown);
    if (!reason.empty()) return fail(std::move(reason));
  }
  // Across fields, so the schema cannot say it.
  if (window_s > window_cap_s) {
    return fail("photos.window_s = " + std::to_string(window_s) +
                " s is longer than photos.window_cap_s = " + std::to_string(window_cap_s) +
                " s: shorten the window or raise the cap");
  }
  return true;
}

std::optional<ShutterMode> ParseShutterMode(std::string_view text) {
  if (text == "interval") return ShutterMode::kInterval;
  if (text == "best-phase") return ShutterMode::kBestPhase;
  return std::nullopt;
}

std::string_view ToString(ShutterMode mode) {
  return mode == ShutterMode::kBestPhase ? "best-phase" : "interval";
}

std::optional<PhotoCameraKind> ParsePhotoCameraKind(std::string_view text) {
  if (text == "agent") return PhotoCameraKind::kAgent;
  if (text == "gphoto2") return PhotoCameraKind::kGphoto2;
  return std::nullopt;
}

std::string_view ToString(PhotoCameraKind camera) {
  return camera == PhotoCameraKind::kGphoto2 ? "gphoto2" : "agent";
}

}  // namespace kapfix::agent
