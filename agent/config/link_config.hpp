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
  // Issue 15: commands a station may send (counted per CurveZMQ key; plain: per IP address),
  // beyond which it is refused with ERROR_CODE_RATE_LIMITED, and from all stations together
  // (the shared burst is twice the shared rate).
  double command_rate_per_s = 20;        // [commands/s] per station, sustained
  double command_burst = 40;             // [commands] per station, at once
  double all_commands_rate_per_s = 100;  // [commands/s] from all stations together

  // Addresses are tcp://HOST:PORT (HOST may be *), ipc://PATH or inproc://NAME and differ;
  // heartbeat 100…60000 ms; command rates 0.1…100000/s (the shared one at least the
  // station's, and its burst, twice it, at least the station's burst), burst 1…1000000.
  bool IsValid(std::string* error) const;
};

}  // namespace kapfix::agent
