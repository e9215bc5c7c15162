// PhotoTaker with a still camera (issue 13): the selected still camera's JPEG is stored as
// it came, with its sidecar, and sent; a still camera that is absent, busy, refusing or gone
// mid-download gives way to the agent's camera, and the sidecar says why; nothing partial
// is kept.
#include <gmock/gmock.h>
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>

#include "agent/photos/photo_taker.hpp"
#include "agent/still_camera/fake_still_camera.hpp"
#include "agent/still_camera/still_camera_trigger.hpp"
#include "tests/agent/support/recording_stream_sink.hpp"
#include "tests/support/temp_dir.hpp"

namespace kapfix::agent {
namespace {

using kapfix::agent::testing::RecordingStreamSink;
using kapfix::agent::testing::WaitUntil;
using kapfix::testing::TempDir;
using ::testing::HasSubstr;
using Behaviour = FakeStillCamera::Behaviour;

std::string ReadAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// A real camera JPEG (aero3.jpg, 640x480 from the OpenCV samples).
std::string CameraJpeg() { return ReadAll(std::string(KAPFIX_OPENCV_DATA_DIR) + "/aero3.jpg"); }

// The agent camera's frame: 64x48, so its photo is told apart from the still camera's.
CapturedFrame AgentFrame() {
  cv::Mat image(48, 64, CV_8UC3);
  cv::RNG rng(7);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  return CapturedFrame{image, 0, 0};
}

kapfix::v1::PhotoMetadata Sidecar(const std::filesystem::path& photo) {
  kapfix::v1::PhotoMetadata metadata;
  EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(ReadAll(PhotoStore::SidecarPath(photo)),
                                                          &metadata)
                  .ok());
  return metadata;
}

std::size_t FilesIn(const std::filesystem::path& dir) {
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir),
                                                std::filesystem::directory_iterator()));
}

struct Rig {
  explicit Rig(bool delete_on_camera = false) {
    auto fake = std::make_unique<FakeStillCamera>(jpeg);
    camera = fake.get();
    taker.SetStillCamera(std::make_shared<StillCameraTrigger>(std::move(fake), delete_on_camera));
    taker.SetCamera(kapfix::v1::PHOTO_CAMERA_GPHOTO2);
  }
  // One commanded photo of the next frame, written; its path in the store.
  std::filesystem::path TakeOne(const std::string& note) {
    std::string error;
    std::string name;
    EXPECT_TRUE(taker.Request(note, &error, &name)) << error;
    taker.OnStep(AgentFrame(), FrameOutcome{}, TelemetryRecord{});
    EXPECT_TRUE(WaitUntil([&] { return taker.saved() + taker.failed() >= 1; }));
    return store.dir() / name;
  }

  std::string jpeg = CameraJpeg();
  TempDir temp;
  PhotoStore store{temp.path() / "photos"};
  RecordingStreamSink sink;
  PhotoTaker taker{store, sink, nullptr};
  FakeStillCamera* camera = nullptr;  // owned by the taker's still camera
};

TEST(PhotoTakerCameraTest, StillCameraJpegIsStoredAsItCameWithItsSidecarAndSent) {
  Rig rig;
  const std::filesystem::path photo = rig.TakeOne("tower");
  ASSERT_EQ(rig.taker.saved(), 1u);
  EXPECT_EQ(ReadAll(photo), rig.jpeg);
  const kapfix::v1::PhotoMetadata metadata = Sidecar(photo);
  EXPECT_EQ(metadata.camera(), kapfix::v1::PHOTO_CAMERA_GPHOTO2);
  EXPECT_EQ(metadata.camera_fallback_reason(), "");
  EXPECT_EQ(metadata.note(), "tower");
  EXPECT_EQ(metadata.format(), "jpeg");
  EXPECT_EQ(metadata.width_px(), 640u);
  EXPECT_EQ(metadata.height_px(), 480u);
  ASSERT_TRUE(WaitUntil([&] { return !rig.sink.Messages<kapfix::v1::Photo>().empty(); }));
  std::string sent;
  for (const auto& chunk : rig.sink.Messages<kapfix::v1::Photo>()) sent += chunk.data();
  EXPECT_EQ(sent, rig.jpeg);
  EXPECT_EQ(rig.camera->files().size(), 1u);  // the camera's card keeps its copy by default
}

TEST(PhotoTakerCameraTest, AbsentStillCameraFallsBackToTheAgentCameraWithTheReason) {
  Rig rig;
  rig.camera->Script(Behaviour::kAbsent);
  const std::filesystem::path photo = rig.TakeOne("");
  ASSERT_EQ(rig.taker.saved(), 1u);
  const kapfix::v1::PhotoMetadata metadata = Sidecar(photo);
  EXPECT_EQ(metadata.camera(), kapfix::v1::PHOTO_CAMERA_AGENT);
  EXPECT_EQ(metadata.camera_fallback_reason(), "fake: no camera found");
  EXPECT_EQ(metadata.width_px(), 64u);  // the agent camera's frame
  EXPECT_FALSE(cv::imread(photo.string()).empty());
}

TEST(PhotoTakerCameraTest, BusyStillCameraFallsBackToTheAgentCameraWithTheReason) {
  Rig rig;
  rig.camera->Script(Behaviour::kBusy);
  const kapfix::v1::PhotoMetadata metadata = Sidecar(rig.TakeOne(""));
  EXPECT_EQ(metadata.camera(), kapfix::v1::PHOTO_CAMERA_AGENT);
  EXPECT_EQ(metadata.camera_fallback_reason(), "fake: capture: I/O in progress");
}

TEST(PhotoTakerCameraTest, RefusingStillCameraFallsBackToTheAgentCameraWithTheReason) {
  Rig rig;
  rig.camera->Script(Behaviour::kRefuses);
  const kapfix::v1::PhotoMetadata metadata = Sidecar(rig.TakeOne(""));
  EXPECT_EQ(metadata.camera(), kapfix::v1::PHOTO_CAMERA_AGENT);
  EXPECT_EQ(metadata.camera_fallback_reason(), "fake: capture: unsupported operation");
}

TEST(PhotoTakerCameraTest, StillCameraVanishingMidDownloadKeepsNothingPartialButTheFallbackPhoto) {
  Rig rig;
  rig.camera->Script(Behaviour::kVanishesMidDownload);
  const std::filesystem::path photo = rig.TakeOne("");
  ASSERT_EQ(rig.taker.saved(), 1u);
  EXPECT_EQ(FilesIn(rig.store.dir()), 2u);  // the fallback photo and its sidecar, nothing else
  EXPECT_NE(ReadAll(photo), rig.jpeg.substr(0, rig.jpeg.size() / 2));
  const kapfix::v1::PhotoMetadata metadata = Sidecar(photo);
  EXPECT_EQ(metadata.camera(), kapfix::v1::PHOTO_CAMERA_AGENT);
  EXPECT_THAT(metadata.camera_fallback_reason(), HasSubstr("download: I/O problem"));
  // The reason says where the camera keeps the photo it took.
  EXPECT_THAT(metadata.camera_fallback_reason(), HasSubstr("/store_00010001/DCIM/100FAKE/IMG_1"));
  EXPECT_EQ(rig.store.count(), 1u);
}

TEST(PhotoTakerCameraTest, AgentCameraSelectedNeverTriggersTheStillCamera) {
  Rig rig;
  rig.taker.SetCamera(kapfix::v1::PHOTO_CAMERA_AGENT);
  const kapfix::v1::PhotoMetadata metadata = Sidecar(rig.TakeOne(""));
  EXPECT_EQ(metadata.camera(), kapfix::v1::PHOTO_CAMERA_AGENT);
  EXPECT_EQ(metadata.camera_fallback_reason(), "");
  EXPECT_EQ(rig.camera->opens(), 0);
  EXPECT_EQ(rig.camera->captures(), 0);
}

TEST(PhotoTakerCameraTest, StillCameraSelectedInAnAgentWithoutOneFallsBackSayingSo) {
  TempDir temp;
  PhotoStore store(temp.path() / "photos");
  RecordingStreamSink sink;
  PhotoTaker taker(store, sink, nullptr);
  taker.SetCamera(kapfix::v1::PHOTO_CAMERA_GPHOTO2);
  std::string error;
  std::string name;
  ASSERT_TRUE(taker.Request("", &error, &name)) << error;
  taker.OnStep(AgentFrame(), FrameOutcome{}, TelemetryRecord{});
  ASSERT_TRUE(WaitUntil([&] { return taker.saved() + taker.failed() >= 1; }));
  const kapfix::v1::PhotoMetadata metadata = Sidecar(store.dir() / name);
  EXPECT_EQ(metadata.camera(), kapfix::v1::PHOTO_CAMERA_AGENT);
  EXPECT_EQ(metadata.camera_fallback_reason(), "gphoto2: this agent has no still camera");
}

TEST(PhotoTakerCameraTest, CameraCopyIsDeletedOnlyWhenAskedOnceStored) {
  Rig rig(/*delete_on_camera=*/true);
  const std::filesystem::path photo = rig.TakeOne("");
  ASSERT_EQ(rig.taker.saved(), 1u);
  EXPECT_EQ(ReadAll(photo), rig.jpeg);
  EXPECT_TRUE(WaitUntil([&] { return rig.camera->files().empty(); }));
}

}  // namespace
}  // namespace kapfix::agent
