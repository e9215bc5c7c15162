#include "agent/config/photo_config.hpp"

#include <utility>

#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/settings_schema.hpp"

namespace kapfix::agent {

bool PhotoConfig::IsValid(std::string* error) const {
  auto fail = [error](std::string message) {
    if (error) *error = std::move(message);
    return false;
  };
  if (dir.empty()) return fail("photos.dir: must not be empty");
  // The range is the schema's (Command.set_photo_interval_s).
  std::string reason = kapfix::v1::CheckSetting(
      *kapfix::v1::Command::descriptor(), "set_photo_interval_s", interval_s, "photos.interval_s");
  if (!reason.empty()) return fail(std::move(reason));
  return true;
}

}  // namespace kapfix::agent
