#include "agent/capture/aravis_frame_source.hpp"

#include <gtest/gtest.h>

#include <string>

namespace kapfix::agent {
namespace {

TEST(AravisFrameSourceTest, OpenOnAnUnknownCameraNamesIt) {
  AravisFrameSourceOptions options;
  options.camera_id = "NoSuchVendor-NoSuchCamera-0042";
  AravisFrameSource source(options);
  std::string error;
  EXPECT_FALSE(source.Open(&error));
  EXPECT_NE(error.find("NoSuchVendor-NoSuchCamera-0042"), std::string::npos) << error;
}

TEST(AravisFrameSourceTest, GrabWithoutOpenFailsWithAReason) {
  AravisFrameSource source(AravisFrameSourceOptions{});
  CapturedFrame frame;
  std::string error;
  EXPECT_FALSE(source.Grab(&frame, &error));
  EXPECT_FALSE(error.empty());
}

TEST(AravisFrameSourceTest, HalfASizeIsInvalid) {
  AravisFrameSourceOptions options;
  options.width = 640;
  EXPECT_FALSE(options.IsValid(nullptr));
}

// Aravis's own simulated GenICam camera ("Fake" interface) runs the whole backend — open,
// region, stream, conversion, gain and exposure through GenICam features — without hardware.
class AravisFakeCameraTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!AravisFrameSource::Available()) GTEST_SKIP() << "built without Aravis";
    options_.camera_id = "Fake_1";
    options_.enable_fake_camera = true;
    options_.width = 320;
    options_.height = 240;
  }
  AravisFrameSourceOptions options_;
};

TEST_F(AravisFakeCameraTest, GrabsBgrFramesOfTheRequestedSize) {
  AravisFrameSource source(options_);
  std::string error;
  ASSERT_TRUE(source.Open(&error)) << error;
  CapturedFrame frame;
  ASSERT_TRUE(source.Grab(&frame, &error)) << error;
  EXPECT_EQ(frame.image.type(), CV_8UC3);
  EXPECT_EQ(frame.image.cols, 320);
  EXPECT_EQ(frame.image.rows, 240);
}

TEST_F(AravisFakeCameraTest, FrameIndicesCountUp) {
  AravisFrameSource source(options_);
  std::string error;
  ASSERT_TRUE(source.Open(&error)) << error;
  CapturedFrame frame;
  ASSERT_TRUE(source.Grab(&frame, &error)) << error;
  ASSERT_TRUE(source.Grab(&frame, &error)) << error;
  EXPECT_EQ(frame.index, 1u);
}

TEST_F(AravisFakeCameraTest, GainInsideTheCameraRangeIsAccepted) {
  AravisFrameSource source(options_);
  std::string error;
  ASSERT_TRUE(source.Open(&error)) << error;
  EXPECT_TRUE(source.SetGain(3.0, &error)) << error;
}

TEST_F(AravisFakeCameraTest, GainOutsideTheCameraRangeIsRefusedWithTheRange) {
  AravisFrameSource source(options_);
  std::string error;
  ASSERT_TRUE(source.Open(&error)) << error;
  EXPECT_FALSE(source.SetGain(1e6, &error));
  EXPECT_NE(error.find("outside its range"), std::string::npos) << error;
}

TEST_F(AravisFakeCameraTest, ExposureIsAccepted) {
  AravisFrameSource source(options_);
  std::string error;
  ASSERT_TRUE(source.Open(&error)) << error;
  EXPECT_TRUE(source.SetExposure(5000, &error)) << error;
}

TEST_F(AravisFakeCameraTest, DescribeNamesTheOpenCamera) {
  AravisFrameSource source(options_);
  std::string error;
  ASSERT_TRUE(source.Open(&error)) << error;
  EXPECT_NE(source.Describe().find("Fake_1"), std::string::npos) << source.Describe();
}

}  // namespace
}  // namespace kapfix::agent
