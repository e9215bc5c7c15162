#include "agent/config/photo_config.hpp"

#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/settings_schema.hpp"

namespace kapfix::agent {

bool PhotoConfig::IsValid(std::string* error) const {
  if (dir.empty()) {
    if (error) *error = "photos.dir: must not be empty";
    return false;
  }
  // The range is the schema's (Command.set_photo_interval_s).
  std::string reason = kapfix::v1::CheckSetting(
      *kapfix::v1::Command::descriptor(), "set_photo_interval_s", interval_s, "photos.interval_s");
  if (!reason.empty()) {
    if (error) *error = std::move(reason);
    return false;
  }
  return true;
}

}  // namespace kapfix::agent
