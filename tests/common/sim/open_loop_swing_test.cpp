#include "common/sim/open_loop_swing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

// The swing with the photometric effects off, so that SSD finds exact geometry.
SwingOptions CleanSwing() {
  SwingOptions o;
  o.camera.noise_sigma = 0;
  o.camera.brightness_amplitude = 0;
  return o;
}

// Brute-force SSD: where the `patch` rectangle of `reference` lies in `current`, minus
// where it was.
cv::Point MeasuredDisplacement(const cv::Mat& reference, const cv::Mat& current, cv::Rect patch) {
  cv::Mat ssd;
  cv::matchTemplate(current, reference(patch), ssd, cv::TM_SQDIFF);
  cv::Point best;
  cv::minMaxLoc(ssd, nullptr, nullptr, &best, nullptr);
  return best - patch.tl();
}

TEST(OpenLoopSwingTest, DefaultsAreTheSpecSwing) {
  const SwingOptions o;
  EXPECT_EQ(o.camera.frame_size, cv::Size(300, 300));
  EXPECT_EQ(o.motion.amplitude_px, 100);
  EXPECT_EQ(o.motion.period_frames, 40);
  EXPECT_EQ(o.motion.decay_frames, 400);
  EXPECT_EQ(o.motion.jitter_sigma_px, 2);
  EXPECT_FALSE(o.motion.gusts);
  EXPECT_EQ(o.camera.noise_sigma, 3);
  EXPECT_EQ(o.camera.brightness_amplitude, 0.08);
  EXPECT_EQ(o.camera.brightness_period_frames, 400);
  EXPECT_EQ(o.camera.blur_sigma, 0);
  EXPECT_EQ(o.frames, 400);
  EXPECT_TRUE(o.IsValid(nullptr));
}

TEST(OpenLoopSwingTest, TrueDisplacementSignMatchesBruteForceSsd) {
  const OpenLoopSwing swing(testing::LoadOpenCvPhoto("aero1.jpg"), CleanSwing());
  const cv::Mat reference = swing.Frame(0);
  const cv::Rect patch(120, 120, 60, 60);
  for (int t : {3, 10, 31}) {
    const cv::Point measured = MeasuredDisplacement(reference, swing.Frame(t), patch);
    const cv::Point2d truth = swing.TrueDisplacement(t);
    EXPECT_NEAR(measured.x, truth.x, 1.0) << "frame " << t;
    EXPECT_NEAR(measured.y, truth.y, 1.0) << "frame " << t;
  }
  // The line of sight swings right first, so the content moves left.
  EXPECT_LT(swing.TrueDisplacement(10).x, -90.0);
}

TEST(OpenLoopSwingTest, TrueDisplacementAgainstAnotherReferenceFrame) {
  const OpenLoopSwing swing(testing::LoadOpenCvPhoto("aero1.jpg"), CleanSwing());
  const cv::Rect patch(120, 120, 60, 60);
  const cv::Point measured = MeasuredDisplacement(swing.Frame(25), swing.Frame(33), patch);
  const cv::Point2d truth = swing.TrueDisplacement(33, 25);
  EXPECT_NEAR(measured.x, truth.x, 1.0);
  EXPECT_NEAR(measured.y, truth.y, 1.0);
  EXPECT_EQ(truth, -(swing.LineOfSight(33) - swing.LineOfSight(25)));
  EXPECT_EQ(swing.TrueDisplacement(25, 25), cv::Point2d(0, 0));
}

TEST(OpenLoopSwingTest, SameOptionsGiveIdenticalFramesInAnyOrder) {
  const cv::Mat scene = testing::LoadOpenCvPhoto("aero1.jpg");
  const OpenLoopSwing a(scene, SwingOptions{}), b(scene, SwingOptions{});
  const cv::Mat late = a.Frame(37);
  a.Frame(2);
  EXPECT_EQ(cv::norm(late, b.Frame(37), cv::NORM_INF), 0);
  EXPECT_GT(cv::norm(late, a.Frame(38), cv::NORM_INF), 0);
}

TEST(OpenLoopSwingTest, ForFrameSizeChangesOnlyTheFrame) {
  const SwingOptions o = SwingOptions::ForFrameSize({640, 480});
  EXPECT_EQ(o.camera.frame_size, cv::Size(640, 480));
  EXPECT_EQ(o.motion.amplitude_px, SwingOptions{}.motion.amplitude_px);
  const OpenLoopSwing swing(testing::LoadOpenCvPhoto("aero1.jpg"), o);
  EXPECT_EQ(swing.Frame(10).size(), cv::Size(640, 480));
  EXPECT_GT(swing.camera().upscale_factor(), 1.0);  // 640×480 cannot cover 902×742
}

TEST(OpenLoopSwingTest, FramesOutsideTheSwingThrow) {
  SwingOptions o;
  o.frames = 5;
  const OpenLoopSwing swing(testing::LoadOpenCvPhoto("aero1.jpg"), o);
  EXPECT_EQ(swing.frames(), 5);
  EXPECT_NO_THROW(swing.Frame(4));
  EXPECT_THROW(swing.Frame(5), std::out_of_range);
  EXPECT_THROW(swing.Frame(-1), std::out_of_range);
}

TEST(OpenLoopSwingTest, AmplitudeBeyondTheCameraExcursionIsRejected) {
  SwingOptions o;
  o.motion.amplitude_px = 150;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("excursion"), std::string::npos) << error;
  EXPECT_THROW(OpenLoopSwing(testing::LoadOpenCvPhoto("aero1.jpg"), o), std::invalid_argument);
  o.camera.max_excursion_px = 160;
  EXPECT_TRUE(o.IsValid(nullptr));
}

}  // namespace
}  // namespace kapfix
