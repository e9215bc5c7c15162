#pragma once

#include <cstdint>
#include <filesystem>
#include <mutex>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "kapfix/v1/photo.pb.h"

namespace kapfix::agent {

// The agent's photo folder (SPEC §4): each photo is a JPEG and a JSON sidecar holding its
// PhotoMetadata, both written atomically (temporary file, fsync, rename). The JPEG goes first
// and is removed again if its sidecar cannot be written, so the folder only ever holds
// complete pairs. Thread-safe. The number of photos is counted once, when the store is made
// (file names only, no sidecar read), then kept up to date by Save(): the agent's state, which
// every command consults, costs the same with 0 or 100,000 photos on disk.
class PhotoStore {
 public:
  explicit PhotoStore(std::filesystem::path dir);
  virtual ~PhotoStore() = default;
  PhotoStore(const PhotoStore&) = delete;
  PhotoStore& operator=(const PhotoStore&) = delete;

  // Whether a photo of about `bytes` can be stored now: the folder exists (it is created) and
  // is writable, and the disk has room for twice that. The reason names the folder.
  bool CheckWritable(std::uintmax_t bytes, std::string* error) const;

  // A new, unique file name for a photo captured at `capture_time_us` [µs since epoch], for a
  // photo whose name must be known before it is saved (the reply to take_photo names it).
  std::string NewFileName(std::int64_t capture_time_us);

  // Encodes `image` (BGR) as JPEG and stores it with `metadata`, whose width, height, format
  // and (unless set, from NewFileName) file_name are filled here; returns the completed
  // metadata and the file's bytes.
  // Throws std::runtime_error naming the file and the reason (disk full, no permission).
  kapfix::v1::PhotoMetadata Save(const cv::Mat& image, kapfix::v1::PhotoMetadata metadata,
                                 std::string* jpeg);
  // Stores a file another camera made (PhotoTrigger): `bytes` as they are, with `metadata`,
  // whose width, height and format the caller fills; the file name as in Save. The same
  // guarantees as Save: written atomically, never a file without its sidecar.
  // Virtual: the seam of a slow disk in tests (a store whose fsync takes seconds).
  virtual kapfix::v1::PhotoMetadata SaveFile(const std::string& bytes,
                                             kapfix::v1::PhotoMetadata metadata);
  // `image` (BGR) as the JPEG the store keeps; throws std::runtime_error when it cannot.
  static std::string EncodeJpeg(const cv::Mat& image);

  // Photos whose capture time is at or after `since_us`, oldest first.
  std::vector<kapfix::v1::PhotoMetadata> ListSince(std::int64_t since_us) const;
  // The file of a stored photo; throws std::runtime_error when it cannot be read.
  std::string ReadFile(const std::string& file_name) const;
  std::uint64_t count() const;  // photos in the folder, without reading it
  const std::filesystem::path& dir() const { return dir_; }

  // The sidecar's path for a photo file.
  static std::filesystem::path SidecarPath(const std::filesystem::path& photo);

 private:
  std::filesystem::path dir_;
  mutable std::mutex mutex_;
  std::uint64_t next_serial_ = 1;
  std::uint64_t count_ = 0;  // complete pairs: counted at start, then by Save()
};

}  // namespace kapfix::agent
