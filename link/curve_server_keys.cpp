#include "link/curve_server_keys.hpp"

#include <sys/stat.h>

#include <cstdio>

namespace kapfix::link {

std::optional<CurveServerKeys> ReadCurveServerKeys(const std::string& secret_key_file,
                                                   const std::string& authorized_keys_file,
                                                   std::string* error) {
  std::string why;
  const auto pair = ReadSecretKeyFile(secret_key_file, &why);
  if (!pair) {
    if (error) *error = "link.curve_secret_key_file: " + why;
    return std::nullopt;
  }
  // Whoever can write the list can authorise a station (issue 15, item 13).
  struct stat info {};
  constexpr mode_t kGroupOrOtherWrite = 0022;
  if (::stat(authorized_keys_file.c_str(), &info) == 0 &&
      (info.st_mode & kGroupOrOtherWrite) != 0) {
    if (error) {
      char mode[8];
      std::snprintf(mode, sizeof mode, "%04o", static_cast<unsigned>(info.st_mode & 07777U));
      *error = "link.curve_authorized_keys_file: '" + authorized_keys_file +
               "' is writable by group or others (mode " + mode +
               "), so anyone could authorise a station: chmod go-w it";
    }
    return std::nullopt;
  }
  auto stations = ReadPublicKeyLines(authorized_keys_file, &why);
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

}  // namespace kapfix::link
