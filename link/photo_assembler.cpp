#include "link/photo_assembler.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace kapfix::link {
namespace {

// Whether the chunks received cover [0, total) without a hole: overlapping chunks could
// add up to the size while leaving one.
bool Covers(const std::map<std::uint64_t, std::uint64_t>& chunks, std::uint64_t total) {
  std::uint64_t end = 0;
  for (const auto& [offset, size] : chunks) {
    if (offset > end) return false;
    end = std::max(end, offset + size);
  }
  return end >= total;
}

}  // namespace

bool PhotoAssembler::IsPlainFileName(const std::string& name) {
  return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos &&
         name.find('\0') == std::string::npos;
}

std::optional<AssembledPhoto> PhotoAssembler::Add(const kapfix::v1::Photo& chunk) {
  const std::string& name = chunk.metadata().file_name();
  const std::uint64_t total = chunk.total_bytes();
  const std::uint64_t offset = chunk.offset_bytes();
  const std::uint64_t size = chunk.data().size();
  if (!IsPlainFileName(name) || total == 0 || total > kMaxPhotoBytes || offset > total ||
      size > total - offset) {
    return std::nullopt;
  }
  Partial& photo = partial_[name];
  if (photo.bytes.size() != total) {  // first chunk, or the photo was re-announced resized
    photo = Partial{chunk.metadata(), std::string(total, '\0'), {}, 0};
  }
  const auto [it, inserted] = photo.chunks.emplace(offset, size);
  if (!inserted) return std::nullopt;  // a repeated chunk
  photo.bytes.replace(offset, size, chunk.data());
  photo.received += size;
  if (photo.received < total || !Covers(photo.chunks, total)) return std::nullopt;
  AssembledPhoto done{std::move(photo.metadata), std::move(photo.bytes)};
  partial_.erase(name);
  return done;
}

std::filesystem::path PhotoAssembler::Save(const AssembledPhoto& photo,
                                           const std::filesystem::path& folder) {
  const std::string& name = photo.metadata.file_name();
  if (!IsPlainFileName(name)) throw std::runtime_error("refusing photo name '" + name + "'");
  std::filesystem::path target = folder / name;
  const std::filesystem::path temporary = folder / ("." + name + ".part");
  const auto fail = [&](const std::string& what) {
    const std::string reason = what + " '" + temporary.string() + "': " + std::strerror(errno);
    ::unlink(temporary.c_str());
    throw std::runtime_error(reason);
  };
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail("cannot create");
  std::size_t written = 0;
  while (written < photo.bytes.size()) {
    const ::ssize_t n = ::write(fd, photo.bytes.data() + written, photo.bytes.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ::close(fd);
      fail("cannot write");
    }
    written += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) {
    ::close(fd);
    fail("cannot sync");
  }
  if (::close(fd) != 0) fail("cannot close");
  if (::rename(temporary.c_str(), target.c_str()) != 0) fail("cannot rename");
  return target;
}

}  // namespace kapfix::link
