// PhotoStore: each photo lands as a JPEG and its JSON sidecar, both written atomically; a full
// disk leaves nothing behind; the folder can be listed and read back, by plain names only.
#include "agent/photos/photo_store.hpp"

#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/resource.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/support/temp_dir.hpp"

namespace kapfix::agent {
namespace {

using kapfix::testing::TempDir;

cv::Mat NoisePhoto(cv::Size size) {
  cv::Mat image(size, CV_8UC3);
  cv::RNG rng(7);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  return image;
}

kapfix::v1::PhotoMetadata MetadataAt(std::int64_t capture_time_us) {
  kapfix::v1::PhotoMetadata metadata;
  metadata.set_capture_time_us(capture_time_us);
  metadata.set_pan_angle_deg(1.5F);
  metadata.set_slice(4);
  metadata.set_lens_profile("6mm");
  return metadata;
}

std::vector<std::string> FileNames(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    names.push_back(entry.path().filename().string());
  }
  return names;
}

std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Lowers the process's file size limit for the guard's lifetime, with SIGXFSZ ignored so that
// an oversized write fails with EFBIG instead of killing the test: a full disk without root.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    previous_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    EXPECT_EQ(::getrlimit(RLIMIT_FSIZE, &previous_), 0);
    rlimit lowered = previous_;
    lowered.rlim_cur = bytes;
    EXPECT_EQ(::setrlimit(RLIMIT_FSIZE, &lowered), 0);
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &previous_);
    std::signal(SIGXFSZ, previous_handler_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit previous_{};
  void (*previous_handler_)(int) = nullptr;
};

TEST(PhotoStoreTest, SaveWritesThePhotoAndItsSidecar) {
  TempDir temp;
  PhotoStore store(temp.path());
  const kapfix::v1::PhotoMetadata saved =
      store.Save(NoisePhoto({64, 48}), MetadataAt(1000), nullptr);
  ASSERT_FALSE(saved.file_name().empty());
  EXPECT_TRUE(std::filesystem::is_regular_file(temp.path() / saved.file_name()));
  EXPECT_TRUE(
      std::filesystem::is_regular_file(PhotoStore::SidecarPath(temp.path() / saved.file_name())));
  EXPECT_EQ(FileNames(temp.path()).size(), 2u);  // no temporary file left
}

TEST(PhotoStoreTest, SaveNamesAJpegAndItsSidecarAfterIt) {
  TempDir temp;
  PhotoStore store(temp.path());
  const kapfix::v1::PhotoMetadata saved =
      store.Save(NoisePhoto({64, 48}), MetadataAt(1000), nullptr);
  EXPECT_TRUE(saved.file_name().ends_with(".jpg")) << saved.file_name();
  EXPECT_EQ(PhotoStore::SidecarPath(temp.path() / saved.file_name()).filename().string(),
            saved.file_name() + ".json");
}

TEST(PhotoStoreTest, SaveFillsSizeAndFormat) {
  TempDir temp;
  PhotoStore store(temp.path());
  const kapfix::v1::PhotoMetadata saved =
      store.Save(NoisePhoto({64, 48}), MetadataAt(1000), nullptr);
  EXPECT_EQ(saved.width_px(), 64u);
  EXPECT_EQ(saved.height_px(), 48u);
  EXPECT_EQ(saved.format(), "jpeg");
}

TEST(PhotoStoreTest, SaveReturnsTheBytesOfADecodableJpegOnDisk) {
  TempDir temp;
  PhotoStore store(temp.path());
  std::string jpeg;
  const kapfix::v1::PhotoMetadata saved = store.Save(NoisePhoto({64, 48}), MetadataAt(1000), &jpeg);
  EXPECT_EQ(jpeg, ReadText(temp.path() / saved.file_name()));
  const cv::Mat decoded =
      cv::imdecode(std::vector<unsigned char>(jpeg.begin(), jpeg.end()), cv::IMREAD_COLOR);
  ASSERT_FALSE(decoded.empty());
  EXPECT_EQ(decoded.size(), cv::Size(64, 48));
}

TEST(PhotoStoreTest, SidecarIsJsonWithProtoFieldNames) {
  TempDir temp;
  PhotoStore store(temp.path());
  const kapfix::v1::PhotoMetadata saved =
      store.Save(NoisePhoto({64, 48}), MetadataAt(1234), nullptr);
  const nlohmann::json sidecar =
      nlohmann::json::parse(ReadText(PhotoStore::SidecarPath(temp.path() / saved.file_name())));
  EXPECT_EQ(sidecar.at("file_name").get<std::string>(), saved.file_name());
  EXPECT_EQ(sidecar.at("lens_profile").get<std::string>(), "6mm");
  EXPECT_EQ(sidecar.at("slice").get<int>(), 4);
  EXPECT_DOUBLE_EQ(sidecar.at("pan_angle_deg").get<double>(), 1.5);
  EXPECT_EQ(sidecar.at("width_px").get<int>(), 64);
  // Proto3 JSON writes int64 as a string.
  EXPECT_EQ(sidecar.at("capture_time_us").get<std::string>(), "1234");
  EXPECT_FALSE(sidecar.contains("fileName"));
}

TEST(PhotoStoreTest, TwoPhotosAtTheSameTimeGetDifferentNames) {
  TempDir temp;
  PhotoStore store(temp.path());
  const auto first = store.Save(NoisePhoto({16, 16}), MetadataAt(1000), nullptr);
  const auto second = store.Save(NoisePhoto({16, 16}), MetadataAt(1000), nullptr);
  EXPECT_NE(first.file_name(), second.file_name());
  EXPECT_EQ(store.count(), 2u);
}

TEST(PhotoStoreTest, ListSinceReturnsPhotosFromThatTimeOldestFirst) {
  TempDir temp;
  PhotoStore store(temp.path());
  store.Save(NoisePhoto({16, 16}), MetadataAt(3000), nullptr);
  store.Save(NoisePhoto({16, 16}), MetadataAt(1000), nullptr);
  store.Save(NoisePhoto({16, 16}), MetadataAt(2000), nullptr);
  const std::vector<kapfix::v1::PhotoMetadata> photos = store.ListSince(2000);
  ASSERT_EQ(photos.size(), 2u);
  EXPECT_EQ(photos[0].capture_time_us(), 2000);
  EXPECT_EQ(photos[1].capture_time_us(), 3000);
}

TEST(PhotoStoreTest, ListSinceSkipsASidecarWhosePhotoIsGone) {
  TempDir temp;
  PhotoStore store(temp.path());
  const auto kept = store.Save(NoisePhoto({16, 16}), MetadataAt(1000), nullptr);
  const auto lost = store.Save(NoisePhoto({16, 16}), MetadataAt(2000), nullptr);
  std::filesystem::remove(temp.path() / lost.file_name());
  const std::vector<kapfix::v1::PhotoMetadata> photos = store.ListSince(0);
  ASSERT_EQ(photos.size(), 1u);
  EXPECT_EQ(photos[0].file_name(), kept.file_name());
}

TEST(PhotoStoreTest, ListSinceOfAMissingFolderIsEmpty) {
  TempDir temp;
  const PhotoStore store(temp.path() / "never-made");
  EXPECT_TRUE(store.ListSince(0).empty());
}

TEST(PhotoStoreTest, ReadFileReturnsTheStoredBytes) {
  TempDir temp;
  PhotoStore store(temp.path());
  std::string jpeg;
  const auto saved = store.Save(NoisePhoto({32, 32}), MetadataAt(1000), &jpeg);
  EXPECT_EQ(store.ReadFile(saved.file_name()), jpeg);
}

TEST(PhotoStoreTest, ReadFileRefusesANameWithASlash) {
  TempDir temp;
  std::filesystem::create_directories(temp.path() / "photos" / "sub");
  std::ofstream(temp.path() / "photos" / "sub" / "x.jpg") << "secret";
  std::ofstream(temp.path() / "outside.jpg") << "secret";
  const PhotoStore store(temp.path() / "photos");
  EXPECT_THROW(store.ReadFile("sub/x.jpg"), std::runtime_error);
  EXPECT_THROW(store.ReadFile("../outside.jpg"), std::runtime_error);
  EXPECT_THROW(store.ReadFile((temp.path() / "outside.jpg").string()), std::runtime_error);
}

TEST(PhotoStoreTest, ReadFileOfAnUnknownPhotoThrows) {
  TempDir temp;
  const PhotoStore store(temp.path());
  EXPECT_THROW(store.ReadFile("photo-1-1.jpg"), std::runtime_error);
}

TEST(PhotoStoreTest, CheckWritableCreatesAMissingFolder) {
  TempDir temp;
  const PhotoStore store(temp.path() / "a" / "b");
  std::string error;
  EXPECT_TRUE(store.CheckWritable(1024, &error)) << error;
  EXPECT_TRUE(std::filesystem::is_directory(temp.path() / "a" / "b"));
}

TEST(PhotoStoreTest, CheckWritableRefusesAFolderThatIsAFileAndNamesIt) {
  TempDir temp;
  const std::filesystem::path file = temp.path() / "photos";
  std::ofstream(file) << "not a folder";
  const PhotoStore store(file);
  std::string error;
  EXPECT_FALSE(store.CheckWritable(1024, &error));
  EXPECT_NE(error.find(file.string()), std::string::npos) << error;
}

TEST(PhotoStoreTest, CheckWritableRefusesAPhotoLargerThanTheFreeSpace) {
  TempDir temp;
  const PhotoStore store(temp.path());
  const std::uintmax_t available = std::filesystem::space(temp.path()).available;
  std::string error;
  EXPECT_FALSE(store.CheckWritable(available, &error));  // needs twice the photo's size
  EXPECT_NE(error.find("disk full"), std::string::npos) << error;
}

TEST(PhotoStoreTest, SaveOnAFullDiskThrowsNamingTheFileAndLeavesNothing) {
  TempDir temp;
  PhotoStore store(temp.path());
  const cv::Mat photo = NoisePhoto({640, 480});  // a JPEG of several hundred KiB
  std::string message;
  {
    const FileSizeLimit limit(rlim_t{10} * 1024);
    try {
      store.Save(photo, MetadataAt(1000), nullptr);
    } catch (const std::runtime_error& e) {
      message = e.what();
    }
  }
  ASSERT_FALSE(message.empty()) << "Save did not throw";
  EXPECT_NE(message.find("photo-1000-1.jpg"), std::string::npos) << message;
  EXPECT_TRUE(FileNames(temp.path()).empty());  // no .jpg, .json or .part
  EXPECT_EQ(store.count(), 0u);
}

// A real full disk, as issue 5 asks: a 64 KiB tmpfs, where the write fails with ENOSPC.
// Mounting needs root (CAP_SYS_ADMIN); without it the test is skipped, and the file size
// limit above stands in for the full disk.
TEST(PhotoStoreTest, SaveOnAFullTinyTmpfsThrowsNamingTheFileAndLeavesNothing) {
  TempDir temp;
  const std::filesystem::path tiny = temp.path() / "tiny";
  std::filesystem::create_directory(tiny);
  if (::mount("kapfix-test", tiny.c_str(), "tmpfs", 0, "size=64k") != 0) {
    GTEST_SKIP() << "cannot mount a tmpfs here (" << std::strerror(errno) << "); needs root";
  }
  std::string message;
  {
    PhotoStore store(tiny);
    try {
      store.Save(NoisePhoto({640, 480}), MetadataAt(1000), nullptr);
    } catch (const std::runtime_error& e) {
      message = e.what();
    }
    EXPECT_EQ(store.count(), 0u);
  }
  const std::vector<std::string> left = FileNames(tiny);
  ::umount2(tiny.c_str(), MNT_DETACH);
  ASSERT_FALSE(message.empty()) << "Save did not throw on a full tmpfs";
  EXPECT_NE(message.find("photo-1000-1.jpg"), std::string::npos) << message;
  EXPECT_TRUE(left.empty()) << left.front();  // no .jpg, .json or .part
}

TEST(PhotoStoreTest, SaveWorksAgainOnceTheDiskHasRoom) {
  TempDir temp;
  PhotoStore store(temp.path());
  {
    const FileSizeLimit limit(rlim_t{10} * 1024);
    EXPECT_THROW(store.Save(NoisePhoto({640, 480}), MetadataAt(1000), nullptr), std::runtime_error);
  }
  store.Save(NoisePhoto({640, 480}), MetadataAt(2000), nullptr);
  EXPECT_EQ(store.count(), 1u);
}

}  // namespace
// Issue 15, item 5: every command's state read every sidecar (439 ms at 5,000 photos). The
// count is taken once from the file names, then kept by Save(): proven by a folder emptied
// behind the store's back, which the count does not notice.
TEST(PhotoStoreTest, CountIsTakenOnceFromTheNamesThenKeptWithoutReadingTheFolder) {
  TempDir temp;
  constexpr int kPhotos = 1000;  // the count is what is checked, not time: 1,000 is enough
  for (int i = 0; i < kPhotos; ++i) {
    const std::filesystem::path photo = temp.path() / ("photo-1-" + std::to_string(i) + ".jpg");
    std::ofstream(photo) << "x";
    std::ofstream(PhotoStore::SidecarPath(photo)) << "not read";
  }
  std::ofstream(temp.path() / "photo-2-1.jpg") << "no sidecar: not a photo";
  PhotoStore store(temp.path());
  EXPECT_EQ(store.count(), static_cast<std::uint64_t>(kPhotos));
  for (const auto& entry : std::filesystem::directory_iterator(temp.path())) {
    std::filesystem::remove(entry.path());
  }
  EXPECT_EQ(store.count(), static_cast<std::uint64_t>(kPhotos));
  store.Save(NoisePhoto({64, 48}), MetadataAt(1000), nullptr);
  EXPECT_EQ(store.count(), static_cast<std::uint64_t>(kPhotos) + 1);
}

}  // namespace kapfix::agent
