#pragma once

#include <string>

namespace kapfix::agent {

// The "video" section: the JPEG downlink to the station (SPEC §4: stale frames are dropped,
// the control loop never waits for it). Defaults: resources/README.md.
struct VideoConfig {
  double fps = 10;     // [frames/s] at most; 0 = no video
  int quality = 80;    // JPEG quality 1…100
  double scale = 0.5;  // frame size factor before encoding, (0, 1]

  bool IsValid(std::string* error) const;
};

}  // namespace kapfix::agent
