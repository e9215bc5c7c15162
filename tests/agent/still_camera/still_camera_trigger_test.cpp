// StillCameraTrigger over the fake camera: a whole JPEG comes back with its size and the
// camera's path; RAW files and truncated JPEGs are refused with the place the photo stays;
// a camera that went away is detected again at the next photo.
#include "agent/still_camera/still_camera_trigger.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "agent/still_camera/fake_still_camera.hpp"

namespace kapfix::agent {
namespace {

using ::testing::HasSubstr;
using Behaviour = FakeStillCamera::Behaviour;

std::string CameraJpeg() {
  std::ifstream in(std::string(KAPFIX_OPENCV_DATA_DIR) + "/aero3.jpg", std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

struct Rig {
  explicit Rig(std::string file = CameraJpeg()) {
    auto fake = std::make_unique<FakeStillCamera>(std::move(file));
    camera = fake.get();
    trigger = std::make_unique<StillCameraTrigger>(std::move(fake));
  }
  FakeStillCamera* camera = nullptr;
  std::unique_ptr<StillCameraTrigger> trigger;
};

TEST(StillCameraTriggerTest, GivesTheCamerasJpegWithItsSizeAndPath) {
  Rig rig;
  TakenPhoto photo;
  std::string error;
  ASSERT_TRUE(rig.trigger->Take({}, &photo, &error)) << error;
  EXPECT_EQ(photo.bytes, CameraJpeg());
  EXPECT_EQ(photo.format, "jpeg");
  EXPECT_EQ(photo.width_px, 640u);
  EXPECT_EQ(photo.height_px, 480u);
  EXPECT_EQ(photo.camera, kapfix::v1::PHOTO_CAMERA_GPHOTO2);
  EXPECT_EQ(photo.camera_path, "/store_00010001/DCIM/100FAKE/IMG_1.JPG");
  EXPECT_THAT(rig.trigger->Describe(), HasSubstr("Fake EOS on usb:001,002"));
}

TEST(StillCameraTriggerTest, OpensTheCameraOnceForManyPhotos) {
  Rig rig;
  for (int i = 0; i < 3; ++i) {
    TakenPhoto photo;
    std::string error;
    ASSERT_TRUE(rig.trigger->Take({}, &photo, &error)) << error;
  }
  EXPECT_EQ(rig.camera->opens(), 1);
  EXPECT_EQ(rig.camera->captures(), 3);
}

TEST(StillCameraTriggerTest, RawFileIsRefusedAndStaysOnTheCamera) {
  Rig rig;
  rig.camera->Script(Behaviour::kGivesRaw);
  TakenPhoto photo;
  std::string error;
  EXPECT_FALSE(rig.trigger->Take({}, &photo, &error));
  EXPECT_EQ(rig.trigger->last_fault(), StillCameraFault::kRefused);
  EXPECT_THAT(error, HasSubstr("image/x-canon-cr2 file, not a JPEG: set its image quality"));
  EXPECT_THAT(error, HasSubstr("stays on the camera as /store_00010001/DCIM/100FAKE/IMG_1.CR2"));
  EXPECT_EQ(rig.camera->files().size(), 1u);
  EXPECT_TRUE(photo.bytes.empty());
}

TEST(StillCameraTriggerTest, TruncatedJpegIsNotGiven) {
  const std::string jpeg = CameraJpeg();
  Rig rig(jpeg.substr(0, jpeg.size() / 3));
  TakenPhoto photo;
  std::string error;
  EXPECT_FALSE(rig.trigger->Take({}, &photo, &error));
  EXPECT_THAT(error, HasSubstr("is not a whole JPEG"));
  EXPECT_TRUE(photo.bytes.empty());
}

TEST(StillCameraTriggerTest, CameraGoneMidDownloadIsDetectedAgainAtTheNextPhoto) {
  Rig rig;
  rig.camera->Script(Behaviour::kVanishesMidDownload);
  TakenPhoto photo;
  std::string error;
  EXPECT_FALSE(rig.trigger->Take({}, &photo, &error));
  EXPECT_EQ(rig.trigger->last_fault(), StillCameraFault::kVanished);
  EXPECT_TRUE(photo.bytes.empty());                     // the half that arrived is not handed on
  EXPECT_FALSE(rig.trigger->Take({}, &photo, &error));  // still unplugged
  EXPECT_EQ(error, "fake: no camera found");
  rig.camera->Script(Behaviour::kSucceeds);  // plugged in again
  ASSERT_TRUE(rig.trigger->Take({}, &photo, &error)) << error;
  EXPECT_EQ(photo.bytes, CameraJpeg());
  EXPECT_EQ(rig.camera->opens(), 3);
}

TEST(StillCameraTriggerTest, BusyCameraStaysOpenForTheNextPhoto) {
  Rig rig;
  rig.camera->Script(Behaviour::kBusy);
  TakenPhoto photo;
  std::string error;
  EXPECT_FALSE(rig.trigger->Take({}, &photo, &error));
  EXPECT_EQ(rig.trigger->last_fault(), StillCameraFault::kBusy);
  rig.camera->Script(Behaviour::kSucceeds);
  ASSERT_TRUE(rig.trigger->Take({}, &photo, &error)) << error;
  EXPECT_EQ(rig.camera->opens(), 1);
}

}  // namespace
}  // namespace kapfix::agent
