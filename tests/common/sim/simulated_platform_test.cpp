#include "common/sim/simulated_platform.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

// A platform with one effect at a time switched on by the test: no motion, no photometric
// effects, servos that do exactly what they are told on the next Step.
SimulatedPlatformOptions Still() {
  SimulatedPlatformOptions o;
  o.kite.amplitude_px = 0;
  o.kite.jitter_sigma_px = 0;
  o.camera.noise_sigma = 0;
  o.camera.brightness_amplitude = 0;
  for (SimulatedServoOptions* servo : {&o.pan, &o.tilt}) {
    servo->latency_frames = 0;
    servo->rate_limit_deg_per_frame = 1000;
    servo->dead_band_deg = 0;
    servo->backlash_deg = 0;
  }
  return o;
}

cv::Mat Scene() { return testing::SmoothTexture({800, 800}, 7, 4.0); }

// Brute-force SSD: where the centre 60×60 of `reference` lies in `current`, minus where it was
// (SPEC §1 displacement).
cv::Point Displacement(const cv::Mat& reference, const cv::Mat& current) {
  const cv::Rect patch(120, 120, 60, 60);
  cv::Mat ssd;
  cv::matchTemplate(current, reference(patch), ssd, cv::TM_SQDIFF);
  cv::Point best;
  cv::minMaxLoc(ssd, nullptr, nullptr, &best, nullptr);
  return best - patch.tl();
}

TEST(SimulatedPlatformTest, RejectsNonPositivePxPerDegree) {
  SimulatedPlatformOptions o;
  o.px_per_deg = 0;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("px per degree"), std::string::npos);
  EXPECT_THROW(SimulatedPlatform(Scene(), o), std::invalid_argument);
}

TEST(SimulatedPlatformTest, PositivePanTurnsTheViewRightAndMovesTheContentLeft) {
  SimulatedPlatform platform(Scene(), Still());
  const cv::Mat reference = platform.Capture();
  platform.CommandPan(2.0);
  platform.Step();
  EXPECT_DOUBLE_EQ(platform.ViewOffset().x, 20.0);  // 2° · 10 px/°
  EXPECT_DOUBLE_EQ(platform.ViewOffset().y, 0.0);
  // So a positive displacement measured in the image asks for a positive pan to correct it.
  EXPECT_EQ(Displacement(reference, platform.Capture()), cv::Point(-20, 0));
}

TEST(SimulatedPlatformTest, PositiveTiltTurnsTheViewDownAndMovesTheContentUp) {
  SimulatedPlatform platform(Scene(), Still());
  const cv::Mat reference = platform.Capture();
  platform.CommandTilt(1.5);
  platform.Step();
  EXPECT_DOUBLE_EQ(platform.ViewOffset().y, 15.0);
  EXPECT_EQ(Displacement(reference, platform.Capture()), cv::Point(0, -15));
}

TEST(SimulatedPlatformTest, ServoLatencyShowsACommandThatManyFramesLater) {
  SimulatedPlatformOptions o = Still();
  o.pan.latency_frames = 1;
  SimulatedPlatform platform(Scene(), o);
  platform.CommandPan(1.0);  // sent after capturing frame 0
  platform.Step();
  EXPECT_EQ(platform.frame(), 1);
  EXPECT_DOUBLE_EQ(platform.ViewOffset().x, 0.0);
  platform.Step();
  EXPECT_EQ(platform.frame(), 2);
  EXPECT_DOUBLE_EQ(platform.ViewOffset().x, 10.0);
}

TEST(SimulatedPlatformTest, WithTheServosStillTheViewOffsetIsTheKiteSwing) {
  SimulatedPlatformOptions o = Still();
  o.kite.amplitude_px = 100;
  o.kite.jitter_sigma_px = 2;
  o.kite.gusts = true;
  SimulatedPlatform platform(Scene(), o);
  const KiteMotion kite(o.kite);
  for (int t = 1; t <= 30; ++t) {
    platform.Step();
    const cv::Point2d expected = kite.LineOfSight(t) - kite.LineOfSight(0);
    EXPECT_NEAR(platform.ViewOffset().x, expected.x, 1e-9) << "frame " << t;
    EXPECT_NEAR(platform.ViewOffset().y, expected.y, 1e-9) << "frame " << t;
  }
}

TEST(SimulatedPlatformTest, BoatRollsTheViewAlongY) {
  SimulatedPlatformOptions o = Still();
  o.motion = SimulatedPlatformOptions::Motion::kBoat;
  o.boat.jitter_sigma_px = 0;
  SimulatedPlatform platform(Scene(), o);
  const BoatMotion boat(o.boat);
  for (int t = 0; t < 30; ++t) platform.Step();
  EXPECT_NEAR(platform.ViewOffset().y, boat.LineOfSight(30).y - boat.LineOfSight(0).y, 1e-9);
  EXPECT_DOUBLE_EQ(platform.ViewOffset().x, 0.0);
  EXPECT_GT(std::abs(platform.ViewOffset().y), 10.0);
}

TEST(SimulatedPlatformTest, ServoCompensatingTheSwingHoldsTheView) {
  SimulatedPlatformOptions o = Still();
  o.kite.amplitude_px = 100;
  SimulatedPlatform platform(Scene(), o);
  const KiteMotion kite(o.kite);
  for (int t = 1; t <= 20; ++t) {
    platform.CommandPan(-kite.LineOfSight(t).x / o.px_per_deg);  // perfect foresight
    platform.Step();
    EXPECT_NEAR(platform.ViewOffset().x, 0.0, 1e-9) << "frame " << t;
    EXPECT_GT(std::abs(platform.OpenLoopOffset().x), 0.0) << "frame " << t;
  }
}

TEST(SimulatedPlatformTest, CapturedFrameCarriesTheAnglesItWasSeenThrough) {
  SimulatedPlatform platform(Scene(), Still());
  platform.CommandPan(3.0);
  platform.CommandTilt(-2.0);
  platform.Step();
  const SimulatedFrame frame = platform.CaptureFrame();
  EXPECT_EQ(frame.frame, 1);
  EXPECT_DOUBLE_EQ(frame.pan_deg, 3.0);
  EXPECT_DOUBLE_EQ(frame.tilt_deg, -2.0);
  EXPECT_EQ(frame.image.size(), cv::Size(300, 300));
  EXPECT_EQ(cv::norm(frame.image, platform.Capture(), cv::NORM_INF), 0.0);
}

TEST(SimulatedPlatformTest, ServoLimitsBoundTheAngle) {
  SimulatedPlatformOptions o = Still();
  o.pan.max_deg = 5;
  SimulatedPlatform platform(Scene(), o);
  platform.CommandPan(50);
  platform.Step();
  EXPECT_DOUBLE_EQ(platform.pan_deg(), 5.0);
  EXPECT_DOUBLE_EQ(platform.ViewOffset().x, 50.0);
}

TEST(SimulatedPlatformTest, FrameDropsLoseAboutTheirShareOfFrames) {
  SimulatedPlatformOptions o;
  o.frame_drop_rate = 0.1;
  const SimulatedPlatform platform(testing::SmoothTexture({700, 700}, 3), o);
  int dropped = 0;
  for (int f = 0; f < 2000; ++f) dropped += platform.FrameDropped(f) ? 1 : 0;
  EXPECT_FALSE(platform.FrameDropped(0));  // the reference frame always arrives
  EXPECT_NEAR(dropped / 2000.0, 0.1, 0.02);
}

TEST(SimulatedPlatformTest, FrameDropRateBeyondHalfIsRejected) {
  SimulatedPlatformOptions o;
  o.frame_drop_rate = 0.6;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("frame drop"), std::string::npos);
}

}  // namespace
}  // namespace kapfix
