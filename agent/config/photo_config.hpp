#pragma once

#include <string>

namespace kapfix::agent {

// The "photos" section: stabilised full-resolution photos, saved on the agent's disk first
// (SPEC §4). How the shutter fires is the operator's: AgentConfig::photo. Defaults:
// resources/README.md.
struct PhotoConfig {
  std::string dir = "/var/lib/kapfix/photos";  // created if missing
  double interval_s = 0;                       // [s] automatic photo period; 0 = on command only

  // A directory, and an interval of 0 or in the schema's range.
  bool IsValid(std::string* error) const;
};

}  // namespace kapfix::agent
