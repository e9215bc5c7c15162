#include "agent/photos/photo_store.hpp"

#include <google/protobuf/util/json_util.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "common/io/atomic_file.hpp"
#include "kapfix/v1/photo_sidecar.hpp"

namespace kapfix::agent {
namespace {

constexpr int kJpegQuality = 95;  // full-resolution photos: near-lossless, still small

std::string ReadAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

}  // namespace

PhotoStore::PhotoStore(std::filesystem::path dir) : dir_(std::move(dir)) {
  // Names only: a JPEG with its sidecar is a photo (Save writes only complete pairs).
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir_, ec)) {
    const std::filesystem::path& path = entry.path();
    if (path.extension() == ".jpg" && std::filesystem::exists(SidecarPath(path), ec)) ++count_;
  }
}

std::string PhotoStore::NewFileName(std::int64_t capture_time_us) {
  std::lock_guard lock(mutex_);
  return "photo-" + std::to_string(capture_time_us) + "-" + std::to_string(next_serial_++) + ".jpg";
}

std::filesystem::path PhotoStore::SidecarPath(const std::filesystem::path& photo) {
  std::filesystem::path sidecar = photo;
  sidecar += ".json";
  return sidecar;
}

bool PhotoStore::CheckWritable(std::uintmax_t bytes, std::string* error) const {
  auto fail = [&](const std::string& why) {
    if (error) *error = "photo folder " + dir_.string() + ": " + why;
    return false;
  };
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) return fail(ec.message());
  if (::access(dir_.c_str(), W_OK) != 0) return fail("not writable");
  const std::filesystem::space_info space = std::filesystem::space(dir_, ec);
  if (ec) return fail(ec.message());
  if (space.available < 2 * bytes) {
    return fail("disk full (" + std::to_string(space.available / 1024) +
                " KiB free, a photo needs about " + std::to_string(bytes / 1024) + " KiB)");
  }
  return true;
}

std::string PhotoStore::EncodeJpeg(const cv::Mat& image) {
  std::vector<unsigned char> encoded;
  if (image.empty() ||
      !cv::imencode(".jpg", image, encoded, {cv::IMWRITE_JPEG_QUALITY, kJpegQuality})) {
    throw std::runtime_error("photo: JPEG encoding failed");
  }
  return {encoded.begin(), encoded.end()};
}

kapfix::v1::PhotoMetadata PhotoStore::Save(const cv::Mat& image, kapfix::v1::PhotoMetadata metadata,
                                           std::string* jpeg) {
  std::string bytes = EncodeJpeg(image);
  metadata.set_width_px(static_cast<std::uint32_t>(image.cols));
  metadata.set_height_px(static_cast<std::uint32_t>(image.rows));
  metadata.set_format("jpeg");
  metadata = SaveFile(bytes, std::move(metadata));
  if (jpeg) *jpeg = std::move(bytes);
  return metadata;
}

kapfix::v1::PhotoMetadata PhotoStore::SaveFile(const std::string& bytes,
                                               kapfix::v1::PhotoMetadata metadata) {
  const std::string name =
      metadata.file_name().empty() ? NewFileName(metadata.capture_time_us()) : metadata.file_name();
  if (name.find('/') != std::string::npos || name.starts_with('.')) {
    throw std::runtime_error("photo: invalid file name '" + name + "'");
  }
  metadata.set_file_name(name);
  const std::string sidecar = kapfix::v1::PhotoSidecarJson(metadata);
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  const std::filesystem::path path = dir_ / name;
  WriteFileAtomically(path, bytes);
  try {
    WriteFileAtomically(SidecarPath(path), sidecar);
  } catch (...) {
    std::filesystem::remove(path, ec);  // a photo without its metadata is not kept
    throw;
  }
  {
    std::lock_guard lock(mutex_);
    ++count_;
  }
  return metadata;
}

std::vector<kapfix::v1::PhotoMetadata> PhotoStore::ListSince(std::int64_t since_us) const {
  std::vector<kapfix::v1::PhotoMetadata> photos;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir_, ec)) {
    const std::filesystem::path& path = entry.path();
    if (path.extension() != ".json") continue;
    kapfix::v1::PhotoMetadata metadata;
    try {
      if (!google::protobuf::util::JsonStringToMessage(ReadAll(path), &metadata).ok()) continue;
    } catch (const std::runtime_error&) {
      continue;  // vanished or unreadable: not a photo this agent can offer
    }
    if (metadata.capture_time_us() >= since_us &&
        std::filesystem::exists(dir_ / metadata.file_name())) {
      photos.push_back(metadata);
    }
  }
  std::sort(photos.begin(), photos.end(), [](const auto& a, const auto& b) {
    return a.capture_time_us() != b.capture_time_us() ? a.capture_time_us() < b.capture_time_us()
                                                      : a.file_name() < b.file_name();
  });
  return photos;
}

std::string PhotoStore::ReadFile(const std::string& file_name) const {
  if (file_name.find('/') != std::string::npos || file_name.starts_with('.')) {
    throw std::runtime_error("photo: invalid file name '" + file_name + "'");
  }
  return ReadAll(dir_ / file_name);
}

std::uint64_t PhotoStore::count() const {
  std::lock_guard lock(mutex_);
  return count_;
}

}  // namespace kapfix::agent
