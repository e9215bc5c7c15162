#pragma once

// Where the agent's photos land on the station: chunks are put back together
// (kapfix::link::PhotoAssembler, any order, repeats ignored) and each complete photo is
// written atomically into the chosen folder next to its metadata sidecar,
// "<file_name>.json" (kapfix::v1::PhotoSidecarJson: the same text as the agent's own sidecar).

#include <QString>
#include <cstdint>
#include <optional>

#include "kapfix/v1/photo.pb.h"
#include "link/photo_assembler.hpp"

namespace kapfix::station {

struct SavedPhoto {
  QString image_path;    // the photo
  QString sidecar_path;  // its metadata
  kapfix::v1::PhotoMetadata metadata;
};

class PhotoStore {
 public:
  explicit PhotoStore(QString folder = {}) : folder_(std::move(folder)) {}

  void setFolder(const QString& folder) { folder_ = folder; }
  const QString& folder() const { return folder_; }

  // The saved photo once `chunk` completes one; std::nullopt while incomplete. Throws
  // std::runtime_error when the folder cannot be written.
  std::optional<SavedPhoto> add(const kapfix::v1::Photo& chunk);

  static QString sidecarPathFor(const QString& image_path);
  // [µs since epoch] the newest capture time among the sidecars in `folder`; 0 when none can
  // be read. A restarted station asks the agent for the photos taken after it.
  static std::int64_t newestCaptureTimeUs(const QString& folder);

 private:
  QString folder_;
  kapfix::link::PhotoAssembler assembler_;
};

}  // namespace kapfix::station
