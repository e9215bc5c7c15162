#pragma once

// Puts a photo back together from its Photo chunks (photo.proto: each chunk carries the
// metadata, its offset and the file size), whatever their order and however often a chunk
// is repeated (the agent resends photos after a link loss), and writes it to a folder.

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include "kapfix/v1/photo.pb.h"

namespace kapfix::link {

struct AssembledPhoto {
  kapfix::v1::PhotoMetadata metadata;
  std::string bytes;  // the whole file
};

class PhotoAssembler {
 public:
  // [bytes] a photo announcing more is refused: 1600×1200 PNG at most ~6 MB, so this only
  // guards memory against a corrupted total_bytes.
  static constexpr std::uint64_t kMaxPhotoBytes = std::uint64_t{256} << 20U;

  // The complete photo once its last missing chunk arrived, else std::nullopt. Chunks that do
  // not fit their announced size, or whose photo name is not a plain file name, are ignored.
  std::optional<AssembledPhoto> Add(const kapfix::v1::Photo& chunk);

  // Photos started but not complete.
  std::size_t incomplete() const { return partial_.size(); }

  // Writes `photo` as folder/metadata.file_name atomically (temporary file, fsync, rename),
  // so a reader never sees half a photo. Throws std::runtime_error on failure.
  static std::filesystem::path Save(const AssembledPhoto& photo,
                                    const std::filesystem::path& folder);

  // A name usable as a file in a folder: not empty, no '/', not "." or "..".
  static bool IsPlainFileName(const std::string& name);

 private:
  struct Partial {
    kapfix::v1::PhotoMetadata metadata;
    std::string bytes;
    std::map<std::uint64_t, std::uint64_t> chunks;  // offset → size received
    std::uint64_t received = 0;                     // [bytes] distinct bytes received
  };
  std::map<std::string, Partial> partial_;  // by file name
};

}  // namespace kapfix::link
