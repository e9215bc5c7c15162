#include "agent/config/video_config.hpp"

#include "kapfix/v1/settings.pb.h"
#include "kapfix/v1/settings_schema.hpp"

namespace kapfix::agent {

bool VideoConfig::IsValid(std::string* error) const {
  // The ranges are the schema's (kapfix.v1.VideoSettings), shared with the command validator.
  const auto& video = *kapfix::v1::VideoSettings::descriptor();
  for (const auto& [field, value, name] :
       {std::tuple{"fps", fps, "video.fps"},
        std::tuple{"jpeg_quality", static_cast<double>(quality), "video.quality"},
        std::tuple{"scale", scale, "video.scale"}}) {
    std::string reason = kapfix::v1::CheckSetting(video, field, value, name);
    if (!reason.empty()) {
      if (error) *error = std::move(reason);
      return false;
    }
  }
  return true;
}

}  // namespace kapfix::agent
