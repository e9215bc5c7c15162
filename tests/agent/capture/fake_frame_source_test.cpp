#include "agent/capture/fake_frame_source.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace kapfix::agent {
namespace {

std::vector<cv::Mat> ThreeFrames() {
  std::vector<cv::Mat> frames;
  for (int i = 0; i < 3; ++i) frames.emplace_back(4, 6, CV_8UC3, cv::Scalar(i, i, i));
  return frames;
}

TEST(FakeFrameSourceTest, ServesTheFramesInOrderAndLoops) {
  FakeFrameSource source(ThreeFrames());
  ASSERT_TRUE(source.Open(nullptr));
  CapturedFrame frame;
  std::vector<int> values;
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(source.Grab(&frame, nullptr));
    values.push_back(frame.image.at<cv::Vec3b>(0, 0)[0]);
  }
  EXPECT_EQ(values, (std::vector<int>{0, 1, 2, 0}));
}

TEST(FakeFrameSourceTest, IndexAndTimeAdvancePerFrame) {
  FakeFrameSource source(ThreeFrames(), 2500);
  ASSERT_TRUE(source.Open(nullptr));
  CapturedFrame frame;
  ASSERT_TRUE(source.Grab(&frame, nullptr));
  ASSERT_TRUE(source.Grab(&frame, nullptr));
  EXPECT_EQ(frame.index, 1u);
  EXPECT_EQ(frame.capture_time_us, 2500);
}

TEST(FakeFrameSourceTest, GrabbedImageIsACopy) {
  FakeFrameSource source(ThreeFrames());
  ASSERT_TRUE(source.Open(nullptr));
  CapturedFrame first;
  ASSERT_TRUE(source.Grab(&first, nullptr));
  first.image.setTo(cv::Scalar(99, 99, 99));
  CapturedFrame frame;
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(source.Grab(&frame, nullptr));  // index 3 = frame 0
  EXPECT_EQ(frame.image.at<cv::Vec3b>(0, 0)[0], 0);
}

TEST(FakeFrameSourceTest, GrabBeforeOpenFails) {
  FakeFrameSource source(ThreeFrames());
  CapturedFrame frame;
  std::string error;
  EXPECT_FALSE(source.Grab(&frame, &error));
  EXPECT_NE(error.find("not open"), std::string::npos) << error;
}

TEST(FakeFrameSourceTest, FailsTheRequestedNumberOfGrabsThenRecovers) {
  FakeFrameSource source(ThreeFrames());
  ASSERT_TRUE(source.Open(nullptr));
  source.FailNextGrabs(2);
  CapturedFrame frame;
  std::string error;
  EXPECT_FALSE(source.Grab(&frame, &error));
  EXPECT_NE(error.find("lost"), std::string::npos) << error;
  EXPECT_FALSE(source.Grab(&frame, nullptr));
  EXPECT_TRUE(source.Grab(&frame, nullptr));
  EXPECT_EQ(frame.index, 0u);
}

TEST(FakeFrameSourceTest, FailOpenSimulatesAMissingCamera) {
  FakeFrameSource source(ThreeFrames());
  source.FailOpen(true);
  std::string error;
  EXPECT_FALSE(source.Open(&error));
  EXPECT_FALSE(error.empty());
  source.FailOpen(false);
  EXPECT_TRUE(source.Open(nullptr));
  EXPECT_EQ(source.open_count(), 1);
}

TEST(FakeFrameSourceTest, KeepsTheSettingsItIsGiven) {
  FakeFrameSource source(ThreeFrames());
  kapfix::v1::CameraSettings settings;
  settings.set_gain_db(6.5);
  settings.set_exposure_us(2000);
  std::string error;
  ASSERT_TRUE(source.Apply(settings, &error)) << error;
  EXPECT_EQ(source.applied().gain_db(), 6.5);
  EXPECT_EQ(source.applied().exposure_us(), 2000);
}

TEST(FakeFrameSourceTest, ALaterSettingReplacesTheEarlierAndKeepsTheRest) {
  FakeFrameSource source(ThreeFrames());
  kapfix::v1::CameraSettings first;
  first.set_gain_db(6);
  first.set_exposure_us(2000);
  ASSERT_TRUE(source.Apply(first, nullptr));
  kapfix::v1::CameraSettings second;
  second.set_gain_db(12);
  ASSERT_TRUE(source.Apply(second, nullptr));
  EXPECT_EQ(source.applied().gain_db(), 12);
  EXPECT_EQ(source.applied().exposure_us(), 2000);
}

TEST(FakeFrameSourceTest, RefusesAValueOutsideTheSchemaRange) {
  FakeFrameSource source(ThreeFrames());
  kapfix::v1::CameraSettings settings;
  settings.set_exposure_us(0);
  std::string error;
  EXPECT_FALSE(source.Apply(settings, &error));
  EXPECT_NE(error.find("exposure_us"), std::string::npos) << error;
  EXPECT_FALSE(source.applied().has_exposure_us());
}

TEST(FakeFrameSourceTest, ASettingItLacksIsRefusedByNameAndTheOthersKept) {
  FakeFrameSource source(ThreeFrames());
  source.LackControl(kapfix::v1::CameraSettings::kAutoExposureFieldNumber);
  kapfix::v1::CameraSettings settings;
  settings.set_gain_db(3);
  settings.set_auto_exposure(true);
  std::string error;
  EXPECT_FALSE(source.Apply(settings, &error));
  EXPECT_EQ(error, "fake camera: auto_exposure = true: this camera has no such control");
  EXPECT_EQ(source.applied().gain_db(), 3);
  EXPECT_FALSE(source.applied().has_auto_exposure());
}

TEST(FakeFrameSourceTest, RejectsGreyFrames) {
  EXPECT_THROW(FakeFrameSource(std::vector<cv::Mat>{cv::Mat(4, 4, CV_8UC1)}),
               std::invalid_argument);
}

TEST(FakeFrameSourceTest, RejectsAnEmptyFrameList) {
  EXPECT_THROW(FakeFrameSource(std::vector<cv::Mat>{}), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix::agent
