#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "agent/config/agent_config.hpp"
#include "kapfix/v1/settings.pb.h"

namespace kapfix::agent {

// One line of `kapfix-agent --preflight`.
struct PreflightCheck {
  bool pass = false;
  std::string what;    // "camera", "servos", "agent key"…
  std::string detail;  // what was found
  std::string fix;     // on failure: what to do

  // "PASS camera: aravis 127.0.0.1, one 640x480 frame" / "FAIL …; fix: …".
  std::string Line() const;
};

struct PreflightOptions {
  bool simulate = false;  // --sim: camera and servos are simulated; devices are not checked
  // [bytes] the photo folder's free space below which the check fails.
  std::uintmax_t min_free_bytes = 200ull << 20;
  // The camera photos are taken with (--photo-camera): gphoto2 adds the still camera's line.
  kapfix::v1::PhotoCamera photo_camera = kapfix::v1::PHOTO_CAMERA_AGENT;
};

// Everything that stops a flight, checked without flying (issue 10): the configuration, the
// CurveZMQ key files (present, readable, the secret one not readable by others), each
// configured device (the camera opens and gives one frame; the servo controller opens, which
// reads a Maestro's parameters; nothing is moved), the photo folder (writable, free space)
// and the clock (a board without a real-time clock and no network time boots in 1970, and
// photos would be misdated).
std::vector<PreflightCheck> RunPreflight(const AgentConfig& config,
                                         const PreflightOptions& options);

}  // namespace kapfix::agent
