#pragma once

// What the agent's sockets need for CurveZMQ (SPEC §5, issue 5): its own secret key, and the
// stations it accepts. Without it a server speaks plain ZMTP (loopback or --insecure only;
// the agent checks that, not the server).

#include <optional>
#include <string>
#include <vector>

#include "link/curve_key_file.hpp"

namespace kapfix::link {

struct CurveServerKeys {
  std::string secret_key;  // the agent's, Z85 (its public key is what stations are given)
  // Every station allowed to connect; a connection with any other key is refused in the
  // handshake, before a single message of it reaches the server.
  std::vector<PublicKeyEntry> authorized_stations;
};

// The agent's secret key file and its authorised-keys file (link.curve_secret_key_file,
// link.curve_authorized_keys_file); std::nullopt and why when either is unreadable or
// malformed, or when it authorises nobody.
std::optional<CurveServerKeys> ReadCurveServerKeys(const std::string& secret_key_file,
                                                   const std::string& authorized_keys_file,
                                                   std::string* error);

}  // namespace kapfix::link
