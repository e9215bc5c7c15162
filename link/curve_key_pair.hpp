#pragma once

// CurveZMQ keys (SPEC §5, issue 5): the agent and every station each have a key pair; the
// agent knows the public keys of the stations it accepts, and each station knows the agent's
// public key. Keys travel as Z85 text (40 characters for 32 bytes), as ZeroMQ takes them.

#include <optional>
#include <string>
#include <string_view>

namespace kapfix::link {

struct CurveKeyPair {
  std::string public_key;  // Z85, 40 characters
  std::string secret_key;  // Z85, 40 characters; never logged, never sent

  bool operator==(const CurveKeyPair&) const = default;
};

// CurveZMQ on a station's side: its own key pair (whose public half the agent lists) and the
// agent's public key (which proves the agent is the one it claims to be).
struct CurveClientKeys {
  CurveKeyPair station;
  std::string agent_public_key;  // Z85
};

// A fresh key pair from libsodium's random source (through ZeroMQ). Throws
// std::runtime_error when ZeroMQ was built without CURVE.
CurveKeyPair GenerateCurveKeyPair();

// True when `z85` is 40 Z85 characters, i.e. decodes to a 32-byte key.
bool IsCurveKey(std::string_view z85);

// The public key that belongs to `secret_key` (Z85); std::nullopt when it is not a key.
std::optional<std::string> CurvePublicKeyOf(std::string_view secret_key);

// A pair whose halves are keys and belong together; otherwise false and why (the secret key
// itself never appears in the message).
bool IsValidKeyPair(const CurveKeyPair& pair, std::string* error);

}  // namespace kapfix::link
