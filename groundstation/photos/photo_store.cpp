#include "groundstation/photos/photo_store.hpp"

#include <google/protobuf/util/json_util.h>

#include <QDir>
#include <QFile>
#include <QSaveFile>
#include <algorithm>
#include <stdexcept>
#include <string>

#include "kapfix/v1/photo_sidecar.hpp"

namespace kapfix::station {

QString PhotoStore::sidecarPathFor(const QString& image_path) {
  return image_path + QStringLiteral(".json");
}

std::int64_t PhotoStore::newestCaptureTimeUs(const QString& folder) {
  std::int64_t newest = 0;
  const QDir dir(folder);
  for (const QString& name : dir.entryList({QStringLiteral("*.json")}, QDir::Files)) {
    QFile file(dir.filePath(name));
    if (!file.open(QIODevice::ReadOnly)) continue;
    const QByteArray json = file.readAll();
    kapfix::v1::PhotoMetadata metadata;
    // A sidecar that does not parse (someone else's file) is skipped, not fatal.
    if (!google::protobuf::util::JsonStringToMessage(
             std::string(json.constData(), static_cast<std::size_t>(json.size())), &metadata)
             .ok()) {
      continue;
    }
    newest = std::max(newest, metadata.capture_time_us());
  }
  return newest;
}

std::optional<SavedPhoto> PhotoStore::add(const kapfix::v1::Photo& chunk) {
  auto photo = assembler_.Add(chunk);
  if (!photo) return std::nullopt;
  if (!QDir().mkpath(folder_)) {
    throw std::runtime_error("cannot create the photo folder " + folder_.toStdString());
  }
  SavedPhoto saved;
  saved.metadata = photo->metadata;
  saved.image_path = QString::fromStdString(
      kapfix::link::PhotoAssembler::Save(*photo, folder_.toStdString()).string());

  const std::string json = kapfix::v1::PhotoSidecarJson(photo->metadata);
  saved.sidecar_path = sidecarPathFor(saved.image_path);
  QSaveFile sidecar(saved.sidecar_path);
  if (!sidecar.open(QIODevice::WriteOnly) ||
      sidecar.write(json.data(), static_cast<qint64>(json.size())) !=
          static_cast<qint64>(json.size()) ||
      !sidecar.commit()) {
    throw std::runtime_error("cannot write " + saved.sidecar_path.toStdString());
  }
  return saved;
}

}  // namespace kapfix::station
