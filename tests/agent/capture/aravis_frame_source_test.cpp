#include "agent/capture/aravis_frame_source.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
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

using kapfix::v1::CameraSettings;

// [0…255] the mean of the next frame's values; -1 when Grab fails.
double MeanOfNextFrame(AravisFrameSource& source) {
  CapturedFrame frame;
  if (!source.Grab(&frame, nullptr)) return -1;
  return cv::mean(frame.image)[0];
}

// Whether one of the next 16 frames (more than the stream's queue) has a mean that `holds`;
// false at the first failed Grab.
template <typename Predicate>
bool SomeOfTheNextFrames(AravisFrameSource& source, Predicate holds) {
  for (int i = 0; i < 16; ++i) {
    const double mean = MeanOfNextFrame(source);
    if (mean < 0) return false;
    if (holds(mean)) return true;
  }
  return false;
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

TEST_F(AravisFakeCameraTest, GainOutsideTheCameraRangeIsRefusedNamingItAndTheRange) {
  AravisFrameSource source(options_);
  std::string error;
  ASSERT_TRUE(source.Open(&error)) << error;
  CameraSettings settings;
  settings.set_gain_db(1e6);
  EXPECT_FALSE(source.Apply(settings, &error));
  EXPECT_NE(error.find("Aravis camera 'Fake_1': gain_db = 1e+06 dB: outside its range"),
            std::string::npos)
      << error;
}

// Aravis's fake camera draws its frames brighter with a longer exposure and a higher gain
// (its pattern's scale is 1 + gain + log10(exposure / 10 ms)): what the settings did shows in
// the frames. A few frames were filled before the change; the count is bounded, not timed.
TEST_F(AravisFakeCameraTest, AShortExposureReachesTheCameraAndDarkensItsFrames) {
  AravisFrameSource source(options_);
  std::string error;
  ASSERT_TRUE(source.Open(&error)) << error;
  const double before = MeanOfNextFrame(source);
  ASSERT_GT(before, 50) << "the fake camera's frames at its default exposure";
  CameraSettings settings;
  settings.set_exposure_us(1000);  // scale 1 + log10(0.1) = 0: black
  ASSERT_TRUE(source.Apply(settings, &error)) << error;
  EXPECT_TRUE(SomeOfTheNextFrames(source, [](double mean) { return mean < 1; }));
}

TEST_F(AravisFakeCameraTest, AHigherGainReachesTheCameraAndBrightensItsFrames) {
  AravisFrameSource source(options_);
  std::string error;
  ASSERT_TRUE(source.Open(&error)) << error;
  const double before = MeanOfNextFrame(source);
  CameraSettings settings;
  settings.set_gain_db(3);  // scale 4
  ASSERT_TRUE(source.Apply(settings, &error)) << error;
  EXPECT_TRUE(SomeOfTheNextFrames(source, [before](double mean) { return mean > before + 50; }));
}

// Aravis's fake camera has GainAuto but no ExposureAuto: automatic exposure is refused by
// name, and switching it off needs nothing (the camera is manual).
TEST_F(AravisFakeCameraTest, AutomaticExposureOnACameraWithoutItIsRefusedByName) {
  AravisFrameSource source(options_);
  std::string error;
  ASSERT_TRUE(source.Open(&error)) << error;
  CameraSettings on;
  on.set_auto_exposure(true);
  EXPECT_FALSE(source.Apply(on, &error));
  EXPECT_EQ(error,
            "Aravis camera 'Fake_1': auto_exposure = true: the camera has no ExposureAuto feature");
  CameraSettings off;
  off.set_auto_exposure(false);
  EXPECT_TRUE(source.Apply(off, &error)) << error;
}

TEST_F(AravisFakeCameraTest, SettingsBeforeOpenAreRefusedNamingTheCamera) {
  AravisFrameSource source(options_);
  CameraSettings settings;
  settings.set_gain_db(3);
  std::string error;
  EXPECT_FALSE(source.Apply(settings, &error));
  EXPECT_EQ(error, "Aravis camera 'Fake_1': not open");
}

TEST_F(AravisFakeCameraTest, DescribeNamesTheOpenCamera) {
  AravisFrameSource source(options_);
  std::string error;
  ASSERT_TRUE(source.Open(&error)) << error;
  EXPECT_NE(source.Describe().find("Fake_1"), std::string::npos) << source.Describe();
}

}  // namespace
}  // namespace kapfix::agent
