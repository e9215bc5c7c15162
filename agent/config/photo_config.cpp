#include "agent/config/photo_config.hpp"

#include <utility>

namespace kapfix::agent {

bool PhotoConfig::IsValid(std::string* error) const {
  auto fail = [error](std::string message) {
    if (error) *error = std::move(message);
    return false;
  };
  if (dir.empty()) return fail("photos.dir: must not be empty");
  return true;
}

}  // namespace kapfix::agent
