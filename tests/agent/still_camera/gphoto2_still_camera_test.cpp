// The real libgphoto2 path on a machine without a still camera (this one, CI): the library is
// loaded, detects nothing, and says so cleanly; the trigger passes the reason on.
#include "agent/still_camera/gphoto2_still_camera.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "agent/still_camera/still_camera_trigger.hpp"

namespace kapfix::agent {
namespace {

using ::testing::HasSubstr;

TEST(Gphoto2StillCameraTest, NoCameraOnThisMachineIsReportedAsAbsent) {
  if (!Gphoto2StillCamera::Available()) GTEST_SKIP() << "built without libgphoto2";
  Gphoto2StillCamera camera;
  std::string model;
  StillCameraError error;
  if (camera.Open(&model, &error)) GTEST_SKIP() << "a still camera is connected: " << model;
  EXPECT_EQ(error.fault, StillCameraFault::kAbsent) << error.message;
  EXPECT_THAT(error.message, HasSubstr("no camera found"));
}

TEST(Gphoto2StillCameraTest, CaptureWithoutAnOpenCameraFailsClearly) {
  Gphoto2StillCamera camera;
  std::string path;
  StillCameraError error;
  EXPECT_FALSE(camera.Capture(&path, &error));
  EXPECT_EQ(error.fault, StillCameraFault::kAbsent);
  EXPECT_FALSE(error.message.empty());
}

TEST(Gphoto2StillCameraTest, TriggerOverTheLibraryGivesTheReasonWhenNoCameraIsFound) {
  if (!Gphoto2StillCamera::Available()) GTEST_SKIP() << "built without libgphoto2";
  StillCameraTrigger trigger(std::make_unique<Gphoto2StillCamera>());
  TakenPhoto photo;
  std::string error;
  if (trigger.Take({}, &photo, &error)) GTEST_SKIP() << "a still camera is connected";
  EXPECT_THAT(error, HasSubstr("gphoto2: no camera found"));
  EXPECT_TRUE(photo.bytes.empty());
}

}  // namespace
}  // namespace kapfix::agent
