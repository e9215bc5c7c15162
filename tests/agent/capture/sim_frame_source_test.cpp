#include "agent/capture/sim_frame_source.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

namespace kapfix::agent {
namespace {

using kapfix::v1::CameraSettings;

// The simulated camera over aero1.jpg; the same seed gives the same frames.
SimFrameSource Camera() {
  const cv::Mat scene =
      cv::imread(std::string(KAPFIX_OPENCV_DATA_DIR) + "/aero1.jpg", cv::IMREAD_COLOR);
  return SimFrameSource(std::make_shared<SimulatedPlatform>(scene, SimulatedPlatformOptions{}), 30);
}

cv::Mat FirstFrame(SimFrameSource& source) {
  CapturedFrame frame;
  if (!source.Open(nullptr) || !source.Grab(&frame, nullptr)) return {};
  return frame.image;
}

TEST(SimFrameSourceTest, AGainReachesTheFramesAsBrightness) {
  SimFrameSource plain = Camera();
  SimFrameSource gained = Camera();
  CameraSettings settings;
  settings.set_gain_db(6);
  std::string error;
  ASSERT_TRUE(gained.Apply(settings, &error)) << error;
  const cv::Mat without = FirstFrame(plain);
  const cv::Mat with = FirstFrame(gained);
  ASSERT_FALSE(without.empty());
  cv::Mat expected;
  without.convertTo(expected, -1, std::pow(10.0, 6.0 / 20));  // saturating, as a sensor
  EXPECT_EQ(cv::norm(with, expected, cv::NORM_INF), 0);
  EXPECT_GT(cv::mean(with)[0], cv::mean(without)[0] * 1.3);
}

TEST(SimFrameSourceTest, AFixedExposureIsRefusedNamingItAndTheCamera) {
  SimFrameSource source = Camera();
  CameraSettings settings;
  settings.set_exposure_us(2000);
  std::string error;
  EXPECT_FALSE(source.Apply(settings, &error));
  EXPECT_EQ(error, source.Describe() + ": exposure_us = 2000 µs: this camera has no such control");
}

TEST(SimFrameSourceTest, AutomaticExposureIsWhatItDoes) {
  SimFrameSource source = Camera();
  CameraSettings on;
  on.set_auto_exposure(true);
  std::string error;
  EXPECT_TRUE(source.Apply(on, &error)) << error;
  CameraSettings off;
  off.set_auto_exposure(false);
  EXPECT_FALSE(source.Apply(off, &error));
  EXPECT_NE(error.find("auto_exposure = false: the simulated camera is always automatically"),
            std::string::npos)
      << error;
}

}  // namespace
}  // namespace kapfix::agent
