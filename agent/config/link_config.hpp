#pragma once

#include <string>

namespace kapfix::agent {

// The "link" section (SPEC §5, issue 5). Defaults: resources/README.md.
struct LinkConfig {
  // Loopback by default: without CurveZMQ keys the agent refuses to listen on the network
  // (unless --insecure). A field setup sets "tcp://*:5555" / "tcp://*:5556" with keys.
  std::string command_address = "tcp://127.0.0.1:5555";  // ROUTER: commands and replies
  std::string stream_address = "tcp://127.0.0.1:5556";   // PUB: telemetry, video, reports, photos
  int heartbeat_ms = 1000;                               // [ms] interval of heartbeats both ways
  // CurveZMQ: the agent's secret key file and the file listing the station public keys it
  // accepts (kapfix-keygen writes both). Both empty = no encryption, which the agent allows
  // only on loopback or with --insecure; both or neither must be set.
  std::string curve_secret_key_file;
  std::string curve_authorized_keys_file;

  // Addresses are tcp://HOST:PORT (HOST may be *), ipc://PATH or inproc://NAME and differ;
  // heartbeat 100…60000 ms.
  bool IsValid(std::string* error) const;
};

}  // namespace kapfix::agent
