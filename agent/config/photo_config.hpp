#pragma once

#include <string>

namespace kapfix::agent {

// The "photos" section: stabilised full-resolution photos, saved on the agent's disk first
// (SPEC §4). When and how photos are taken is the operator's: AgentConfig::photo. Defaults:
// resources/README.md.
struct PhotoConfig {
  std::string dir = "/var/lib/kapfix/photos";  // created if missing

  // A directory.
  bool IsValid(std::string* error) const;
};

}  // namespace kapfix::agent
