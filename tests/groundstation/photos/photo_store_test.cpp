#include "groundstation/photos/photo_store.hpp"

#include <gtest/gtest.h>

#include <QFile>
#include <QTemporaryDir>

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

TEST(PhotoStore, NewestCaptureTimeOfAnEmptyFolderIsZero) {
  const QTemporaryDir dir;
  EXPECT_EQ(PhotoStore::newestCaptureTimeUs(dir.path()), 0);
}

}  // namespace
}  // namespace kapfix::station
