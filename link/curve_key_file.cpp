#include "link/curve_key_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

namespace kapfix::link {
namespace {

constexpr mode_t kSecretFileMode = 0600;
constexpr mode_t kGroupOrOtherAccess = 0077;

std::string Quoted(const std::filesystem::path& path) { return "'" + path.string() + "'"; }

bool Fail(std::string* error, const std::string& message) {
  if (error) *error = message;
  return false;
}

std::string_view Trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

bool IsCommentOrBlank(std::string_view line) {
  const std::string_view trimmed = Trim(line);
  return trimmed.empty() || trimmed.front() == '#';
}

// Writes `text` into a new file of mode `mode`: O_EXCL unless overwriting, so that an
// existing key is never clobbered by accident; fsync so that a key reported written is.
bool WriteNewFile(const std::filesystem::path& path, const std::string& text, mode_t mode,
                  bool overwrite, std::string* error) {
  if (overwrite) {
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
  }
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, mode);
  if (fd < 0) {
    const int why = errno;
    if (why == EEXIST) {
      return Fail(error, Quoted(path) + " already exists (use --force to replace it)");
    }
    return Fail(error, "cannot create " + Quoted(path) + ": " + std::strerror(why));
  }
  // The umask may only have narrowed the mode; this makes it exact.
  bool ok = ::fchmod(fd, mode) == 0;
  std::size_t written = 0;
  while (ok && written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    ok = n > 0;
    if (ok) written += static_cast<std::size_t>(n);
  }
  ok = ok && ::fsync(fd) == 0;
  const int why = errno;
  ok = (::close(fd) == 0) && ok;
  if (!ok) {
    std::error_code ignored;
    std::filesystem::remove(path, ignored);  // no half-written key left behind
    return Fail(error, "cannot write " + Quoted(path) + ": " + std::strerror(why));
  }
  return true;
}

std::optional<std::string> ReadWhole(const std::filesystem::path& path, std::string* error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    Fail(error, "cannot read key file " + Quoted(path) + ": " + std::strerror(errno));
    return std::nullopt;
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

bool WriteSecretKeyFile(const std::filesystem::path& path, const CurveKeyPair& pair,
                        std::string_view name, bool overwrite, std::string* error) {
  std::string why;
  if (!IsValidKeyPair(pair, &why)) return Fail(error, "not writing " + Quoted(path) + ": " + why);
  const std::string text = "# kapfix CurveZMQ secret key \"" + std::string(name) +
                           "\": keep it private, give out the .pub file only\n"
                           "public-key = " +
                           pair.public_key + "\nsecret-key = " + pair.secret_key + "\n";
  return WriteNewFile(path, text, kSecretFileMode, overwrite, error);
}

bool WritePublicKeyFile(const std::filesystem::path& path, const std::string& public_key,
                        std::string_view name, bool overwrite, std::string* error) {
  if (!IsCurveKey(public_key)) {
    return Fail(error, "not writing " + Quoted(path) + ": the public key is not 40 Z85 characters");
  }
  constexpr mode_t kPublicFileMode = 0644;
  return WriteNewFile(path, public_key + " " + std::string(name) + "\n", kPublicFileMode, overwrite,
                      error);
}

std::optional<CurveKeyPair> ReadSecretKeyFile(const std::filesystem::path& path,
                                              std::string* error) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) {
    Fail(error, "cannot read secret key file " + Quoted(path) + ": " + std::strerror(errno));
    return std::nullopt;
  }
  if ((info.st_mode & kGroupOrOtherAccess) != 0) {
    std::ostringstream mode;
    mode << std::oct << (info.st_mode & 0777U);
    Fail(error, "secret key file " + Quoted(path) + " is open to other users (mode 0" + mode.str() +
                    "): run chmod 600 on it");
    return std::nullopt;
  }
  const auto text = ReadWhole(path, error);
  if (!text) return std::nullopt;
  CurveKeyPair pair;
  std::istringstream lines(*text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    if (IsCommentOrBlank(line)) continue;
    const auto equals = line.find('=');
    const std::string_view key = Trim(std::string_view(line).substr(0, equals));
    const std::string_view value = equals == std::string::npos
                                       ? std::string_view{}
                                       : Trim(std::string_view(line).substr(equals + 1));
    std::string* field = key == "public-key"   ? &pair.public_key
                         : key == "secret-key" ? &pair.secret_key
                                               : nullptr;
    if (equals == std::string::npos || field == nullptr) {
      Fail(error, Quoted(path) + " line " + std::to_string(number) +
                      ": expected 'public-key = …' or 'secret-key = …'");
      return std::nullopt;
    }
    *field = std::string(value);
  }
  std::string why;
  if (!IsValidKeyPair(pair, &why)) {
    Fail(error, "secret key file " + Quoted(path) + ": " + why);
    return std::nullopt;
  }
  return pair;
}

std::optional<std::vector<PublicKeyEntry>> ReadPublicKeyLines(const std::filesystem::path& path,
                                                              std::string* error) {
  const auto text = ReadWhole(path, error);
  if (!text) return std::nullopt;
  std::vector<PublicKeyEntry> entries;
  std::istringstream lines(*text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    if (IsCommentOrBlank(line)) continue;
    const std::string_view trimmed = Trim(line);
    const auto space = trimmed.find_first_of(" \t");
    PublicKeyEntry entry;
    entry.key = std::string(trimmed.substr(0, space));
    if (space != std::string_view::npos) entry.name = std::string(Trim(trimmed.substr(space)));
    if (!IsCurveKey(entry.key)) {
      Fail(error, Quoted(path) + " line " + std::to_string(number) +
                      ": not a public key (expected 40 Z85 characters, then an optional name)");
      return std::nullopt;
    }
    entries.push_back(std::move(entry));
  }
  return entries;
}

std::optional<std::string> ReadPublicKeyFile(const std::filesystem::path& path,
                                             std::string* error) {
  auto entries = ReadPublicKeyLines(path, error);
  if (!entries) return std::nullopt;
  if (entries->size() != 1) {
    Fail(error, "public key file " + Quoted(path) + " holds " + std::to_string(entries->size()) +
                    " keys; expected exactly one");
    return std::nullopt;
  }
  return std::move(entries->front().key);
}

}  // namespace kapfix::link
