#pragma once

// The key files kapfix-keygen writes and the agent, kapfix-ctl and kapfix-station read.
//
// - NAME.key, the secret key file, mode 0600 (a file others can read is refused):
//       # kapfix CurveZMQ secret key "NAME": keep it private, give out NAME.pub only
//       public-key = <Z85>
//       secret-key = <Z85>
// - NAME.pub, the public key file, one line, so that `cat NAME.pub >> authorized_keys`
//   authorises a station:
//       <Z85> NAME
// - An authorised-keys file: such lines, one per station; blank lines and lines starting
//   with '#' are ignored.
//
// Errors name the file, and the line where there is one.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "link/curve_key_pair.hpp"

namespace kapfix::link {

struct PublicKeyEntry {
  std::string key;   // Z85, 40 characters
  std::string name;  // what follows the key on its line (who it belongs to); may be empty

  bool operator==(const PublicKeyEntry&) const = default;
};

// Creates `path` with mode 0600 (never wider, whatever the umask) and syncs it to disk.
// Refuses to replace an existing file unless `overwrite`.
bool WriteSecretKeyFile(const std::filesystem::path& path, const CurveKeyPair& pair,
                        std::string_view name, bool overwrite, std::string* error);
bool WritePublicKeyFile(const std::filesystem::path& path, const std::string& public_key,
                        std::string_view name, bool overwrite, std::string* error);

// A secret key file: both keys, checked to belong together; refused when its mode lets
// anyone but the owner read or write it.
std::optional<CurveKeyPair> ReadSecretKeyFile(const std::filesystem::path& path,
                                              std::string* error);
// Every key line of a public key file or an authorised-keys file (possibly none).
std::optional<std::vector<PublicKeyEntry>> ReadPublicKeyLines(const std::filesystem::path& path,
                                                              std::string* error);
// A public key file: exactly one key line.
std::optional<std::string> ReadPublicKeyFile(const std::filesystem::path& path, std::string* error);

}  // namespace kapfix::link
