// PhotoTaker: a requested or periodic photo of the stabilised frame is stored by the writer
// thread, then published in chunks that each carry the metadata; stored photos can be sent
// again; a photo is refused up front when the folder cannot take it.
#include "agent/photos/photo_taker.hpp"

#include <gtest/gtest.h>
#include <sys/mount.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "kapfix/v1/settings_schema.hpp"
#include "tests/agent/support/recording_stream_sink.hpp"
#include "tests/support/temp_dir.hpp"

namespace kapfix::agent {
namespace {

// The agent's initial photo settings with an automatic photo every `seconds` (0 = off).
kapfix::v1::PhotoSettings Every(float seconds) {
  auto photo = kapfix::v1::InitialSettings<kapfix::v1::PhotoSettings>();
  photo.set_interval_s(seconds);
  return photo;
}

using kapfix::agent::testing::RecordingStreamSink;
using kapfix::testing::TempDir;

constexpr std::int64_t kFramePeriodUs = 100'000;  // a 10 fps camera

CapturedFrame Frame(std::uint64_t index) {
  cv::Mat image(48, 64, CV_8UC3);
  cv::RNG rng(index + 1);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  return CapturedFrame{image, static_cast<std::int64_t>(index) * kFramePeriodUs, index};
}

TelemetryRecord Record(std::uint64_t index) {
  TelemetryRecord record;
  record.index = index;
  record.capture_time_us = static_cast<std::int64_t>(index) * kFramePeriodUs;
  return record;
}

void Step(PhotoTaker& taker, std::uint64_t index) {
  taker.OnStep(Frame(index), FrameOutcome{}, Record(index));
}

std::string Concatenated(const std::vector<kapfix::v1::Photo>& chunks) {
  std::string bytes;
  for (const auto& chunk : chunks) bytes += chunk.data();
  return bytes;
}

struct Rig {
  TempDir temp;
  PhotoStore store{temp.path() / "photos"};
  RecordingStreamSink sink;
  PhotoTaker taker{store, sink, [] { return std::string("6mm"); }};
};

TEST(PhotoTakerTest, RequestedPhotoOfTheNextFrameIsStoredAndPublished) {
  Rig rig;
  std::string error;
  ASSERT_TRUE(rig.taker.Request("tower", &error)) << error;
  Step(rig.taker, 0);
  rig.taker.Flush();
  EXPECT_EQ(rig.taker.saved(), 1u);
  const std::vector<kapfix::v1::PhotoMetadata> stored = rig.store.ListSince(0);
  ASSERT_EQ(stored.size(), 1u);
  const auto chunks = rig.sink.Messages<kapfix::v1::Photo>();
  EXPECT_EQ(chunks.front().metadata().file_name(), stored[0].file_name());
  EXPECT_EQ(Concatenated(chunks), rig.store.ReadFile(stored[0].file_name()));
}

TEST(PhotoTakerTest, RequestTakesOnlyOnePhoto) {
  Rig rig;
  std::string error;
  ASSERT_TRUE(rig.taker.Request("", &error)) << error;
  for (std::uint64_t i = 0; i < 5; ++i) Step(rig.taker, i);
  rig.taker.Flush();
  EXPECT_EQ(rig.taker.saved(), 1u);
  EXPECT_EQ(rig.store.count(), 1u);
}

// Issue 15, item 9: five take_photo before one frame were five OK replies and one photo.
TEST(PhotoTakerTest, FiveRequestsBeforeOneFrameMakeFiveFilesEachWithItsNameAndNote) {
  Rig rig;
  std::vector<std::string> names;
  for (int i = 0; i < 5; ++i) {
    std::string error;
    std::string name;
    ASSERT_TRUE(rig.taker.Request("note " + std::to_string(i), &error, &name)) << error;
    names.push_back(name);
  }
  Step(rig.taker, 0);
  rig.taker.Flush();
  EXPECT_EQ(rig.taker.saved(), 5u);
  const std::vector<kapfix::v1::PhotoMetadata> stored = rig.store.ListSince(0);
  ASSERT_EQ(stored.size(), 5u);
  for (int i = 0; i < 5; ++i) {
    ASSERT_TRUE(std::filesystem::exists(rig.store.dir() / names[i])) << names[i];
    const auto it = std::find_if(stored.begin(), stored.end(),
                                 [&](const auto& m) { return m.file_name() == names[i]; });
    ASSERT_NE(it, stored.end()) << names[i];
    EXPECT_EQ(it->note(), "note " + std::to_string(i));  // read back from the sidecar
  }
}

// Issue 15, item 10: interval photos kept filling a volume that commanded photos were refused
// on. A 4 MiB tmpfs has less than the reserve (twice about 3 MiB) but room for these photos.
TEST(PhotoTakerTest, IntervalPhotosKeepTheFreeSpaceReserve) {
  TempDir temp;
  const std::filesystem::path small = temp.path() / "small";
  std::filesystem::create_directory(small);
  if (::mount("kapfix-test", small.c_str(), "tmpfs", 0, "size=4m") != 0) {
    GTEST_SKIP() << "cannot mount a tmpfs here (" << std::strerror(errno) << "); needs root";
  }
  std::uint64_t saved = 0;
  std::uint64_t failed = 0;
  {
    PhotoStore store(small);
    RecordingStreamSink sink;
    PhotoTaker taker(store, sink, nullptr);
    taker.SetSettings(Every(0.5F));
    for (std::uint64_t i = 0; i < 30; ++i) Step(taker, i);  // 3 s of camera time
    taker.Flush();
    saved = taker.saved();
    failed = taker.failed();
  }
  std::error_code ec;
  const std::size_t files =
      static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(small, ec), {}));
  ::umount2(small.c_str(), MNT_DETACH);
  EXPECT_EQ(saved, 0u);
  EXPECT_GE(failed, 5u);
  EXPECT_EQ(files, 0u);
}

TEST(PhotoTakerTest, NoPhotoWithoutARequestOrAnInterval) {
  Rig rig;
  for (std::uint64_t i = 0; i < 5; ++i) Step(rig.taker, i);
  rig.taker.Flush();
  EXPECT_EQ(rig.taker.saved(), 0u);
  EXPECT_EQ(rig.sink.size(), 0u);
}

TEST(PhotoTakerTest, PhotoCarriesTheStepsMeasurements) {
  Rig rig;
  std::string error;
  ASSERT_TRUE(rig.taker.Request("", &error)) << error;
  TelemetryRecord record = Record(3);
  record.displacement_x_px = 4.25;
  record.displacement_y_px = -1.75;
  record.angle_pan_deg = 2.5;
  record.angle_tilt_deg = -1.0;
  record.slice = 6;
  record.confidence = 0.75;
  rig.taker.OnStep(Frame(3), FrameOutcome{}, record);
  rig.taker.Flush();
  ASSERT_FALSE(rig.sink.Messages<kapfix::v1::Photo>().empty());
  const kapfix::v1::PhotoMetadata m = rig.sink.Messages<kapfix::v1::Photo>().front().metadata();
  EXPECT_EQ(m.displacement().x_px(), 4);
  EXPECT_FLOAT_EQ(m.displacement().x_subpx(), 0.25F);
  EXPECT_EQ(m.displacement().y_px(), -2);
  EXPECT_FLOAT_EQ(m.displacement().y_subpx(), 0.25F);
  EXPECT_FLOAT_EQ(m.pan_angle_deg(), 2.5F);
  EXPECT_FLOAT_EQ(m.tilt_angle_deg(), -1.0F);
  EXPECT_EQ(m.slice(), 6u);
  EXPECT_FLOAT_EQ(m.confidence(), 0.75F);
  EXPECT_EQ(m.lens_profile(), "6mm");
  EXPECT_EQ(m.width_px(), 64u);
  EXPECT_EQ(m.height_px(), 48u);
}

// Issue 13: the stored sidecar carries the shot's quality, the shutter's account and the note.
TEST(PhotoTakerTest, SidecarCarriesTheQualityFieldsAndTheNote) {
  Rig rig;
  std::string error;
  TelemetryRecord before = Record(2);
  before.found = true;
  before.displacement_x_px = 1.0;
  before.displacement_y_px = 1.0;
  rig.taker.OnStep(Frame(2), FrameOutcome{}, before);
  ASSERT_TRUE(rig.taker.Request("tower", &error)) << error;
  TelemetryRecord record = Record(3);
  record.found = true;
  record.displacement_x_px = 4.0;  // moved (3, 4) px since frame 2; 5 px off the reference
  record.displacement_y_px = 5.0;
  FrameOutcome outcome;
  outcome.patch = cv::Rect(8, 8, 16, 16);
  rig.taker.OnStep(Frame(3), outcome, record);
  rig.taker.Flush();
  const std::vector<kapfix::v1::PhotoMetadata> stored = rig.store.ListSince(0);  // the sidecars
  ASSERT_EQ(stored.size(), 1u);
  const kapfix::v1::PhotoMetadata& m = stored[0];
  EXPECT_EQ(m.note(), "tower");
  EXPECT_NEAR(m.residual_offset_px(), std::hypot(4.0, 5.0), 1e-5);
  EXPECT_NEAR(m.view_speed_px_per_frame(), 5.0, 1e-5);
  // 10 ms of a 100 ms frame: a tenth of the frame's travel.
  EXPECT_NEAR(m.view_blur_px(), 0.5, 1e-5);
  EXPECT_FALSE(m.lock_lost());
  EXPECT_EQ(m.shutter(), kapfix::v1::SHUTTER_INTERVAL);
  EXPECT_FLOAT_EQ(m.shutter_wait_s(), 0.0F);
  EXPECT_EQ(m.shutter_reason(), "interval shutter: at once");
  EXPECT_FLOAT_EQ(m.exposure_ms(), 10.0F);
  EXPECT_EQ(m.camera(), kapfix::v1::PHOTO_CAMERA_AGENT);
  EXPECT_GT(m.sharpness_frame(), 0.0F);  // a random-noise frame is all detail
  EXPECT_GT(m.sharpness_patch(), 0.0F);
  EXPECT_NE(m.sharpness_patch(), m.sharpness_frame());
}

TEST(PhotoTakerTest, LostLockIsMarkedInTheSidecar) {
  Rig rig;
  std::string error;
  ASSERT_TRUE(rig.taker.Request("", &error)) << error;
  TelemetryRecord record = Record(0);
  record.found = false;
  record.lock_lost = true;
  rig.taker.OnStep(Frame(0), FrameOutcome{}, record);
  rig.taker.Flush();
  const auto saved = rig.taker.Saved();
  ASSERT_EQ(saved.size(), 1u);
  EXPECT_TRUE(saved[0].lock_lost());
  EXPECT_FLOAT_EQ(saved[0].view_speed_px_per_frame(), 0.0F);  // not measured
}

TEST(PhotoTakerTest, IntervalTakesAPhotoEveryNSecondsOfCaptureTime) {
  Rig rig;
  rig.taker.SetSettings(Every(1.0F));
  for (std::uint64_t i = 0; i <= 30; ++i) Step(rig.taker, i);  // 0 … 3 s of camera time
  rig.taker.Flush();
  EXPECT_EQ(rig.taker.saved(), 3u);  // at 1, 2 and 3 s
  EXPECT_EQ(rig.taker.failed(), 0u);
}

TEST(PhotoTakerTest, IntervalZeroStopsThePeriodicPhotos) {
  Rig rig;
  rig.taker.SetSettings(Every(1.0F));
  rig.taker.SetSettings(Every(0));
  for (std::uint64_t i = 0; i <= 30; ++i) Step(rig.taker, i);
  rig.taker.Flush();
  EXPECT_EQ(rig.taker.saved(), 0u);
}

TEST(PhotoTakerTest, ResendRepublishesTheStoredPhotosSinceTheGivenTime) {
  Rig rig;
  const cv::Mat image(16, 16, CV_8UC3, cv::Scalar(10, 20, 30));
  kapfix::v1::PhotoMetadata early;
  early.set_capture_time_us(1000);
  kapfix::v1::PhotoMetadata late;
  late.set_capture_time_us(2000);
  rig.store.Save(image, early, nullptr);
  const kapfix::v1::PhotoMetadata kept = rig.store.Save(image, late, nullptr);
  EXPECT_EQ(rig.taker.Resend(1500), std::vector<std::string>{kept.file_name()});
  rig.taker.Flush();
  const auto chunks = rig.sink.Messages<kapfix::v1::Photo>();
  ASSERT_EQ(chunks.size(), 1u);
  EXPECT_EQ(chunks[0].metadata().file_name(), kept.file_name());
  EXPECT_EQ(chunks[0].data(), rig.store.ReadFile(kept.file_name()));
}

TEST(PhotoTakerTest, RequestIsRefusedWithTheReasonWhenTheFolderCannotBeWritten) {
  TempDir temp;
  const std::filesystem::path not_a_folder = temp.path() / "photos";
  std::ofstream(not_a_folder) << "a regular file";
  PhotoStore store(not_a_folder);
  RecordingStreamSink sink;
  PhotoTaker taker(store, sink, nullptr);
  std::string error;
  EXPECT_FALSE(taker.Request("", &error));
  EXPECT_NE(error.find(not_a_folder.string()), std::string::npos) << error;
  Step(taker, 0);  // the refused request takes nothing
  taker.Flush();
  EXPECT_EQ(taker.saved() + taker.failed(), 0u);
}

TEST(PhotoTakerTest, ChunksCoverTheFileWithContiguousOffsets) {
  const std::string bytes(PhotoTaker::kChunkBytes * 5 / 2, 'x');
  kapfix::v1::PhotoMetadata metadata;
  metadata.set_file_name("photo-1-1.jpg");
  const std::vector<kapfix::v1::Photo> chunks = PhotoTaker::Chunks(metadata, bytes);
  ASSERT_EQ(chunks.size(), 3u);
  std::uint64_t offset = 0;
  for (const kapfix::v1::Photo& chunk : chunks) {
    EXPECT_EQ(chunk.offset_bytes(), offset);
    EXPECT_LE(chunk.data().size(), PhotoTaker::kChunkBytes);
    EXPECT_EQ(chunk.total_bytes(), bytes.size());
    offset += chunk.data().size();
  }
  EXPECT_EQ(offset, bytes.size());
  EXPECT_EQ(Concatenated(chunks), bytes);
}

TEST(PhotoTakerTest, EveryChunkCarriesTheMetadata) {
  const std::string bytes(PhotoTaker::kChunkBytes + 1, 'y');
  kapfix::v1::PhotoMetadata metadata;
  metadata.set_file_name("photo-5-2.jpg");
  metadata.set_capture_time_us(5);
  metadata.set_slice(3);
  const std::vector<kapfix::v1::Photo> chunks = PhotoTaker::Chunks(metadata, bytes);
  ASSERT_EQ(chunks.size(), 2u);
  for (const kapfix::v1::Photo& chunk : chunks) {
    EXPECT_EQ(chunk.metadata().file_name(), "photo-5-2.jpg");
    EXPECT_EQ(chunk.metadata().slice(), 3u);
    EXPECT_EQ(chunk.header().capture_time_us(), 5);
  }
}

TEST(PhotoTakerTest, AFileOfExactlyOneChunkIsOneMessage) {
  const std::string bytes(PhotoTaker::kChunkBytes, 'z');
  EXPECT_EQ(PhotoTaker::Chunks(kapfix::v1::PhotoMetadata(), bytes).size(), 1u);
}

}  // namespace
}  // namespace kapfix::agent
