#include "common/io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>

namespace kapfix {
namespace {

[[noreturn]] void Fail(const std::filesystem::path& target, const std::filesystem::path& temp,
                       const std::string& reason) {
  std::error_code ignored;
  std::filesystem::remove(temp, ignored);
  throw std::runtime_error("cannot write '" + target.string() + "': " + reason);
}

}  // namespace

void WriteFileAtomically(const std::filesystem::path& target, std::string_view bytes) {
  const std::filesystem::path temp = target.string() + ".part";
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) Fail(target, temp, std::strerror(errno));
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string reason = n < 0 ? std::strerror(errno) : "short write";
      ::close(fd);
      Fail(target, temp, reason);
    }
    written += static_cast<std::size_t>(n);
  }
  // The data must be on the disk before the rename makes it visible: after a power cut the
  // file is either the old one or the complete new one, never an empty or torn one.
  if (::fsync(fd) != 0) {
    const std::string reason = std::strerror(errno);
    ::close(fd);
    Fail(target, temp, reason);
  }
  if (::close(fd) != 0) Fail(target, temp, std::strerror(errno));
  std::error_code ec;
  std::filesystem::rename(temp, target, ec);
  if (ec) Fail(target, temp, ec.message());
  // And the rename itself: fsync the folder that holds the entry.
  const std::filesystem::path parent =
      target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  const int dir = ::open(parent.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir >= 0) {
    ::fsync(dir);
    ::close(dir);
  }
}

}  // namespace kapfix
