#include "agent/capture/v4l2_frame_source.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>

namespace kapfix::agent {
namespace {

// No camera is attached on the machines that run the tests; these check the failure paths.

TEST(V4l2FrameSourceTest, OpenOnAMissingDeviceNamesItAndSaysWhy) {
  V4l2FrameSourceOptions options;
  options.device = "/dev/video97";
  V4l2FrameSource source(options);
  std::string error;
  EXPECT_FALSE(source.Open(&error));
  EXPECT_NE(error.find("/dev/video97"), std::string::npos) << error;
  EXPECT_NE(error.find("no such device"), std::string::npos) << error;
}

TEST(V4l2FrameSourceTest, IndexMeansDevVideoN) {
  V4l2FrameSourceOptions options;
  options.device = "96";
  V4l2FrameSource source(options);
  EXPECT_EQ(source.DevicePath(), "/dev/video96");
  std::string error;
  EXPECT_FALSE(source.Open(&error));
  EXPECT_NE(error.find("/dev/video96"), std::string::npos) << error;
}

TEST(V4l2FrameSourceTest, RegularFileIsNotAVideoDevice) {
  char path[] = "/tmp/kapfix-v4l2-XXXXXX";
  const int fd = ::mkstemp(path);
  ASSERT_GE(fd, 0);
  ::close(fd);
  V4l2FrameSourceOptions options;
  options.device = path;
  V4l2FrameSource source(options);
  std::string error;
  EXPECT_FALSE(source.Open(&error));
  ::unlink(path);
  EXPECT_NE(error.find(path), std::string::npos) << error;
  EXPECT_NE(error.find("not a video device"), std::string::npos) << error;
}

TEST(V4l2FrameSourceTest, GrabWithoutOpenFailsWithAReason) {
  V4l2FrameSource source(V4l2FrameSourceOptions{});
  CapturedFrame frame;
  std::string error;
  EXPECT_FALSE(source.Grab(&frame, &error));
  EXPECT_NE(error.find("not open"), std::string::npos) << error;
}

TEST(V4l2FrameSourceTest, SettingsWithoutOpenAreRefusedNamingTheCamera) {
  V4l2FrameSource source(V4l2FrameSourceOptions{});
  kapfix::v1::CameraSettings settings;
  settings.set_gain_db(3);
  std::string error;
  EXPECT_FALSE(source.Apply(settings, &error));
  EXPECT_EQ(error, "V4L2 camera /dev/video0: not open");
}

TEST(V4l2FrameSourceTest, InvalidSizeIsRejectedBeforeTouchingTheDevice) {
  V4l2FrameSourceOptions options;
  options.width = 0;
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  V4l2FrameSource source(options);
  EXPECT_FALSE(source.Open(&error));
  EXPECT_NE(error.find("frame size"), std::string::npos) << error;
}

TEST(V4l2FrameSourceTest, FourccMustHaveFourCharacters) {
  V4l2FrameSourceOptions options;
  options.fourcc = "MJPEG";
  EXPECT_FALSE(options.IsValid(nullptr));
}

}  // namespace
}  // namespace kapfix::agent
