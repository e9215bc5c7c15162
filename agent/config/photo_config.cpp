#include "agent/config/photo_config.hpp"

#include <cmath>

namespace kapfix::agent {

bool PhotoConfig::IsValid(std::string* error) const {
  if (dir.empty()) {
    if (error) *error = "photos.dir: must not be empty";
    return false;
  }
  if (!std::isfinite(interval_s) || (interval_s != 0 && (interval_s < 0.1 || interval_s > 86400))) {
    if (error) {
      *error =
          "photos.interval_s: must be 0 (off) or 0.1…86400 s, got " + std::to_string(interval_s);
    }
    return false;
  }
  return true;
}

}  // namespace kapfix::agent
