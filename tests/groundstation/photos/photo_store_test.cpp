#include "groundstation/photos/photo_store.hpp"

#include <gtest/gtest.h>

#include <QFile>
#include <QTemporaryDir>
#include <optional>

#include "kapfix/v1/photo_sidecar.hpp"

namespace kapfix::station {
namespace {

// A whole photo in one chunk, taken at `capture_time_us`.
kapfix::v1::Photo WholePhoto(const std::string& name, std::int64_t capture_time_us) {
  kapfix::v1::Photo photo;
  photo.mutable_metadata()->set_file_name(name);
  photo.mutable_metadata()->set_format("jpeg");
  photo.mutable_metadata()->set_capture_time_us(capture_time_us);
  photo.set_data("not really a jpeg");
  photo.set_total_bytes(photo.data().size());
  return photo;
}

TEST(PhotoStore, NewestCaptureTimeIsTheLatestAmongTheSavedSidecars) {
  const QTemporaryDir dir;
  PhotoStore store(dir.path());
  ASSERT_TRUE(store.add(WholePhoto("a.jpg", 2'000)).has_value());
  ASSERT_TRUE(store.add(WholePhoto("b.jpg", 5'000)).has_value());
  ASSERT_TRUE(store.add(WholePhoto("c.jpg", 3'000)).has_value());
  EXPECT_EQ(PhotoStore::newestCaptureTimeUs(dir.path()), 5'000);
}

TEST(PhotoStore, NewestCaptureTimeIgnoresFilesThatAreNotSidecars) {
  const QTemporaryDir dir;
  PhotoStore store(dir.path());
  ASSERT_TRUE(store.add(WholePhoto("a.jpg", 2'000)).has_value());
  QFile other(dir.filePath(QStringLiteral("notes.json")));
  ASSERT_TRUE(other.open(QIODevice::WriteOnly));
  other.write("{ not json");
  other.close();
  EXPECT_EQ(PhotoStore::newestCaptureTimeUs(dir.path()), 2'000);
}

// One sidecar format: the station writes the text the agent and kapfix-ctl write, every
// field included (a false lock_lost, a 0 px blur).
TEST(PhotoStore, TheSidecarIsTheSharedSidecarText) {
  const QTemporaryDir dir;
  PhotoStore store(dir.path());
  kapfix::v1::Photo photo = WholePhoto("a.jpg", 2'000);
  photo.mutable_metadata()->set_lens_profile("6mm");
  const std::optional<SavedPhoto> saved = store.add(photo);
  ASSERT_TRUE(saved.has_value());
  QFile sidecar(saved->sidecar_path);
  ASSERT_TRUE(sidecar.open(QIODevice::ReadOnly));
  const QByteArray text = sidecar.readAll();
  EXPECT_EQ(text.toStdString(), kapfix::v1::PhotoSidecarJson(photo.metadata()));
  EXPECT_TRUE(text.contains("\"lock_lost\": false")) << text.toStdString();
  EXPECT_TRUE(text.contains("\"view_blur_px\": 0")) << text.toStdString();
}

TEST(PhotoStore, NewestCaptureTimeOfAnEmptyFolderIsZero) {
  const QTemporaryDir dir;
  EXPECT_EQ(PhotoStore::newestCaptureTimeUs(dir.path()), 0);
}

}  // namespace
}  // namespace kapfix::station
