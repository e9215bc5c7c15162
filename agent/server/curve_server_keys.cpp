#include "agent/server/curve_server_keys.hpp"

namespace kapfix::agent {

std::optional<CurveServerKeys> ReadCurveServerKeys(const std::string& secret_key_file,
                                                   const std::string& authorized_keys_file,
                                                   std::string* error) {
  std::string why;
  const auto pair = kapfix::link::ReadSecretKeyFile(secret_key_file, &why);
  if (!pair) {
    if (error) *error = "link.curve_secret_key_file: " + why;
    return std::nullopt;
  }
  auto stations = kapfix::link::ReadPublicKeyLines(authorized_keys_file, &why);
  if (!stations) {
    if (error) *error = "link.curve_authorized_keys_file: " + why;
    return std::nullopt;
  }
  if (stations->empty()) {
    if (error) {
      *error = "link.curve_authorized_keys_file: '" + authorized_keys_file +
               "' lists no station keys, so no station could connect (add a station's .pub "
               "line from kapfix-keygen)";
    }
    return std::nullopt;
  }
  return CurveServerKeys{pair->secret_key, std::move(*stations)};
}

}  // namespace kapfix::agent
